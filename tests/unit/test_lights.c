/* The light table: power-proportional selection, light sampling and its
 * densities, spot falloff, emission sidedness, the no-light error, a
 * directional light's disc. */
#include <string.h>

#include "scene_build.h"
#include "scene/lights.h"
#include "scene/scene.h"

static double lum(il_vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

/* A directional light with a disc of diameter D: its directions lie within
 * D/2 of its centre, uniform over the cap (the mean direction is the
 * centre's times (1 + cos(D/2)) / 2), and the mean of radiance times the
 * cosine is E cos, the irradiance of the point light it replaces, on any
 * surface the disc is wholly above; a point (D = 0) gives the centre
 * exactly; the camera sees it with that irradiance (check_background).
 * Diameters outside [0, 90], or on another light, are refused. */
/* What the camera sees of the disc (il_background_radiance): uniform
 * radiance L inside its radius, none outside, with the irradiance the light
 * gives: int L cos dw over the disc = L pi sin^2(radius) = E on a surface
 * facing it (quadrature over a cap 1.5 times as wide, in polar coordinates
 * about the centre); a point light's has none. */
static void check_background(const il_scene *s, il_vec3 axis, double half, bool disc)
{
    CHECK(s->num_discs == (disc ? 1u : 0u));
    il_frame f = il_frame_from_normal(axis);
    if (!disc) {
        il_vec3 L = il_background_radiance(s, axis);
        CHECK(L.x == 0.0f && L.y == 0.0f && L.z == 0.0f);
        return;
    }
    enum { NT = 3000, NP = 64 };
    double outer = 1.5 * half, sum = 0.0, inside_min = INFINITY, inside_max = 0.0;
    for (int i = 0; i < NT; i++) {
        double t = (i + 0.5) * outer / NT;
        for (int j = 0; j < NP; j++) {
            double p = (j + 0.5) * 2.0 * PI_D / NP;
            il_vec3 local = v3((float)(sin(t) * cos(p)), (float)(sin(t) * sin(p)), (float)cos(t));
            il_vec3 L = il_background_radiance(s, v3_normalize(il_frame_to_world(&f, local)));
            sum += L.x * cos(t) * sin(t) * (outer / NT) * (2.0 * PI_D / NP);
            if (t < 0.99 * half) {
                inside_min = fmin(inside_min, L.x);
                inside_max = fmax(inside_max, L.x);
            } else if (t > 1.01 * half) {
                CHECK(L.x == 0.0f);
            }
        }
    }
    /* The radius is the float cosine's (0.14% wider than asked for the sun's). */
    double want_L = 2.0 / (PI_D * s->discs[0].sin2_radius);
    CHECK_REL(s->discs[0].sin2_radius, sin(half) * sin(half), 3e-3);
    printf("  seen: L %.6g inside (expected %.6g), int L cos dw %.6f (expected 2)\n", inside_min, want_L, sum);
    CHECK(inside_min == inside_max);
    CHECK_REL(inside_min, want_L, 1e-6);
    CHECK_REL(sum, 2.0, 1e-3);
}

static void test_disc(void)
{
    il_error err = {0};
    const float diameters[] = {10.0f, 0.533f, 0.0f};
    for (int k = 0; k < 3; k++) {
        il_scene *s = NULL;
        CHECK_OK(il_scene_create(&s, &err), &err);
        add_quad(s, v3(0, 0, 0), v3(1, 0, 0), v3(0, 0, -1), 0);
        il_light_desc d = {.type = IL_LIGHT_DIRECTIONAL, .direction = {0.3f, -1, 0.2f}, .intensity = {2, 2, 2},
                           .diameter = diameters[k]};
        CHECK_OK(il_scene_add_light(s, &d, &err), &err);
        CHECK_OK(il_scene_commit(s, &err), &err);
        double half = 0.5 * diameters[k] * PI_D / 180.0;
        il_vec3 axis = v3_normalize(v3(-0.3f, 1, -0.2f));
        il_vec3 n = v3_normalize(v3(0.2f, 1, 0.4f)); /* the cap is well above this surface */
        enum { G = 200 };
        double sum_e = 0.0, sum_dir[3] = {0, 0, 0}, worst = 0.0;
        for (int i = 0; i < G * G; i++) {
            il_light_sample ls;
            il_vec2 u = v2(((float)(i % G) + 0.5f) / G, ((float)(i / G) + 0.5f) / G);
            CHECK(il_light_sample_at(s, v3(0, 0, 0), 0.5f, u, &ls));
            double c = v3_dot(ls.wi, axis);
            worst = fmax(worst, acos(fmin(1.0, c)));
            sum_e += ls.radiance.x * v3_dot(ls.wi, n);
            sum_dir[0] += ls.wi.x, sum_dir[1] += ls.wi.y, sum_dir[2] += ls.wi.z;
            if (diameters[k] == 0.0f)
                CHECK(ls.wi.x == axis.x && ls.wi.y == axis.y && ls.wi.z == axis.z && ls.radiance.x == 2.0f);
        }
        double mean_e = sum_e / (G * G), want = 2.0 * v3_dot(axis, n);
        double shrink = (1.0 + cos(half)) / 2.0;
        printf("disc %g deg: farthest %.5f deg (radius %.5f), mean E cos %.6f (expected %.6f)\n",
               (double)diameters[k], worst * 180.0 / PI_D, half * 180.0 / PI_D, mean_e, want);
        CHECK(worst <= half * 1.001 + 2e-4);
        CHECK(worst >= half * 0.98);
        CHECK_REL(mean_e, want, 1e-4);
        CHECK_NEAR(sum_dir[0] / (G * G), axis.x * shrink, 2e-5);
        CHECK_NEAR(sum_dir[1] / (G * G), axis.y * shrink, 2e-5);
        CHECK_NEAR(sum_dir[2] / (G * G), axis.z * shrink, 2e-5);
        check_background(s, axis, half, diameters[k] > 0.0f);
        il_scene_release(s);
    }
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    const il_light_desc bad[] = {
        {.type = IL_LIGHT_DIRECTIONAL, .intensity = {1, 1, 1}, .diameter = 91.0f},
        {.type = IL_LIGHT_DIRECTIONAL, .intensity = {1, 1, 1}, .diameter = -1.0f},
        {.type = IL_LIGHT_DIRECTIONAL, .intensity = {1, 1, 1}, .diameter = NAN},
        {.type = IL_LIGHT_POINT, .intensity = {1, 1, 1}, .diameter = 5.0f}};
    for (int k = 0; k < 4; k++) {
        CHECK(il_scene_add_light(s, &bad[k], &err) == IL_ERR_INVALID);
        printf("bad disc %d: %s\n", k, err.message);
    }
    il_scene_release(s);
}

int main(void)
{
    test_disc();
    il_error err = {0};

    /* No light at all: a clear error. */
    {
        il_scene *s = NULL;
        CHECK_OK(il_scene_create(&s, &err), &err);
        add_quad(s, v3(0, 0, 0), v3(1, 0, 0), v3(0, 0, -1), 0);
        CHECK(il_scene_commit(s, &err) == IL_ERR_INVALID);
        CHECK(strstr(err.message, "no light") != NULL);
        il_scene_release(s);
    }

    /* One light of every kind. */
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    uint32_t emit = 0, emit2 = 0;
    il_material_desc md = {.emission = {2, 3, 4}};
    CHECK_OK(il_scene_add_material(s, &md, &emit, &err), &err);
    il_material_desc md2 = {.emission = {1, 1, 1}, .two_sided = true};
    CHECK_OK(il_scene_add_material(s, &md2, &emit2, &err), &err);
    add_quad(s, v3(0, 0, 0), v3(4, 0, 0), v3(0, 0, -4), 0);           /* floor, not emissive */
    add_quad(s, v3(0, 2, 0), v3(0.5f, 0, 0), v3(0, 0, 0.25f), emit);  /* 1 x 0.5 facing down */
    add_quad(s, v3(2, 1, 0), v3(0, 0.5f, 0), v3(0, 0, 0.5f), emit2);  /* 1 x 1 two-sided */
    il_light_desc point = {.type = IL_LIGHT_POINT, .position = {0, 1, 0}, .intensity = {1, 1, 1}};
    il_light_desc spot = {.type = IL_LIGHT_SPOT, .position = {0, 3, 0}, .intensity = {2, 2, 2},
                          .spot_angle = 30, .spot_exponent = 4}; /* zero direction: down */
    il_light_desc spot45 = {.type = IL_LIGHT_SPOT, .position = {1, 3, 0}, .intensity = {1, 0, 0}};
    il_light_desc dir = {.type = IL_LIGHT_DIRECTIONAL, .direction = {1, -1, 0}, .intensity = {0.5f, 0.5f, 0.5f}};
    il_light_desc dark = {.type = IL_LIGHT_POINT, .position = {0, 1, 0}}; /* zero intensity: left out */
    CHECK_OK(il_scene_add_light(s, &point, &err), &err);
    CHECK_OK(il_scene_add_light(s, &spot, &err), &err);
    CHECK_OK(il_scene_add_light(s, &spot45, &err), &err);
    CHECK_OK(il_scene_add_light(s, &dir, &err), &err);
    CHECK_OK(il_scene_add_light(s, &dark, &err), &err);
    il_environment_desc env = {.radiance = {0.1f, 0.2f, 0.3f}};
    CHECK_OK(il_scene_set_environment(s, &env, &err), &err);
    CHECK_OK(il_scene_commit(s, &err), &err);

    /* 4 user lights, 4 emissive triangles, 1 environment. */
    CHECK(s->num_lights == 9);
    CHECK(s->environment_light == 8);
    CHECK(s->triangle_light[0][0] == IL_NO_LIGHT && s->triangle_light[0][1] == IL_NO_LIGHT);
    CHECK(s->triangle_light[1][0] == 4 && s->triangle_light[1][1] == 5);
    CHECK(s->triangle_light[2][0] == 6 && s->triangle_light[2][1] == 7);
    /* Defaults: zero direction is straight down, zero spot angle is 45 degrees. */
    CHECK_NEAR(s->lights[1].direction.y, -1.0, 1e-7);
    CHECK_NEAR(s->lights[2].cos_cutoff, cos(PI_D / 4.0), 1e-6);

    /* Powers (pbrt-v4 12.x Phi) and selection proportional to them. */
    double R = s->scene_radius;
    double power[9];
    power[0] = 4.0 * PI_D * 1.0;
    power[1] = 2.0 * PI_D * 2.0 * (1.0 - pow(cos(PI_D / 6.0), 5.0)) / 5.0;
    power[2] = 2.0 * PI_D * 0.2126 * (1.0 - cos(PI_D / 4.0));
    power[3] = PI_D * R * R * 0.5;
    power[4] = power[5] = PI_D * lum(v3(2, 3, 4)) * 0.25;   /* each triangle half of 1 x 0.5 */
    power[6] = power[7] = 2.0 * PI_D * 1.0 * 0.5;          /* two-sided, area 0.5 */
    power[8] = 4.0 * PI_D * PI_D * R * R * lum(v3(0.1f, 0.2f, 0.3f));
    double total = 0.0;
    for (int i = 0; i < 9; i++)
        total += power[i];
    for (uint32_t i = 0; i < 9; i++) {
        CHECK_REL(s->lights[i].power, power[i], 1e-4);
        CHECK_REL(s->light_pmf[i], power[i] / total, 1e-4);
    }
    /* Frequencies of selection match the pmf (u on a fine stratified grid). */
    {
        enum { N = 200000 };
        uint32_t count[9] = {0};
        il_light_sample ls;
        for (uint32_t k = 0; k < N; k++) {
            float u = ((float)k + 0.5f) / (float)N;
            il_light_sample_at(s, v3(0, 0.5f, 0.3f), u, v2(0.3f, 0.6f), &ls);
            count[ls.light]++;
        }
        for (uint32_t i = 0; i < 9; i++)
            CHECK_NEAR((double)count[i] / N, s->light_pmf[i], 2.0 / N);
    }

    /* Point light: I/d^2 from its position; the pdf is the selection probability. */
    {
        il_light_sample ls;
        float u = 0.5f * (s->light_cdf[0] + s->light_cdf[1]);
        CHECK(il_light_sample_at(s, v3(0, -1, 0), u, v2(0.5f, 0.5f), &ls));
        CHECK(ls.light == 0 && ls.delta);
        CHECK_NEAR(ls.wi.y, 1.0, 1e-6);
        CHECK_NEAR(ls.dist, 2.0, 1e-6);
        CHECK_NEAR(ls.radiance.x, 0.25, 1e-6);
        CHECK_NEAR(ls.pdf, s->light_pmf[0], 1e-7);
    }
    /* Spot light: I cos^n(angle)/d^2 inside the cone, nothing outside. */
    {
        float u = 0.5f * (s->light_cdf[1] + s->light_cdf[2]);
        il_light_sample ls;
        double a = 20.0 * PI_D / 180.0, d = 2.0;
        il_vec3 p = v3((float)(d * sin(a)), (float)(3.0 - d * cos(a)), 0.0f);
        CHECK(il_light_sample_at(s, p, u, v2(0.5f, 0.5f), &ls));
        CHECK(ls.light == 1 && ls.delta);
        CHECK_REL(ls.radiance.y, 2.0 * pow(cos(a), 4.0) / (d * d), 1e-4);
        CHECK_REL(ls.dist, d, 1e-5);
        /* On the axis: the full intensity. */
        CHECK(il_light_sample_at(s, v3(0, 1, 0), u, v2(0.5f, 0.5f), &ls));
        CHECK_REL(ls.radiance.x, 2.0 / 4.0, 1e-5);
        /* 35 degrees off the axis: outside the 30 degree cut-off. */
        a = 35.0 * PI_D / 180.0;
        p = v3((float)(d * sin(a)), (float)(3.0 - d * cos(a)), 0.0f);
        CHECK(!il_light_sample_at(s, p, u, v2(0.5f, 0.5f), &ls));
        /* Above the spot: outside. */
        CHECK(!il_light_sample_at(s, v3(0, 4, 0), u, v2(0.5f, 0.5f), &ls));
    }
    /* Directional: from -direction, infinitely far, irradiance E. */
    {
        float u = 0.5f * (s->light_cdf[3] + s->light_cdf[4]);
        il_light_sample ls;
        CHECK(il_light_sample_at(s, v3(0, 0, 0), u, v2(0.5f, 0.5f), &ls));
        CHECK(ls.light == 3 && ls.delta && isinf(ls.dist));
        CHECK_NEAR(ls.wi.x, -sqrt(0.5), 1e-6);
        CHECK_NEAR(ls.wi.y, sqrt(0.5), 1e-6);
        CHECK_NEAR(ls.radiance.z, 0.5, 1e-7);
    }
    /* Environment: uniform directions, pdf pmf / (4 pi), as il_light_pdf_environment says. */
    {
        float u = 0.5f * (s->light_cdf[8] + 1.0f);
        il_light_sample ls;
        CHECK(il_light_sample_at(s, v3(0, 0, 0), u, v2(0.3f, 0.7f), &ls));
        CHECK(ls.light == 8 && !ls.delta && isinf(ls.dist));
        CHECK_REL(ls.pdf, s->light_pmf[8] / (4.0 * PI_D), 1e-5);
        CHECK_REL(il_light_pdf_environment(s, v3s(0.0f), ls.wi), ls.pdf, 1e-6);
        CHECK_NEAR(ls.radiance.z, 0.3, 1e-7);
        CHECK_NEAR(v3_length(ls.wi), 1.0, 1e-5);
        il_vec3 er = il_environment_radiance(s, v3(0, 1, 0));
        CHECK_NEAR(er.y, 0.2, 1e-7);
    }

    /* Area lights: the sample's pdf equals il_light_pdf_area, and the mean of
     * 1/pdf over the light's samples is the solid angle it subtends: for a
     * rectangle a x b seen from distance d on its axis,
     * Omega = 4 asin(a b / sqrt((a^2 + 4 d^2)(b^2 + 4 d^2))). */
    {
        il_vec3 p = v3(0, 1, 0); /* 1 below the centre of the 1 x 0.5 emitter */
        double inv_sum = 0.0;
        int n = 0, front = 0, mismatches = 0;
        float lo = s->light_cdf[4], hi = s->light_cdf[6];
        for (int i = 0; i < 256; i++)
            for (int j = 0; j < 64; j++) {
                float us = lo + (hi - lo) * ((float)i + 0.5f) / 256.0f;
                il_vec2 u = v2(((float)j + 0.5f) / 64.0f, (float)((i * 37 + j * 11) % 64 + 0.5) / 64.0f);
                il_light_sample ls;
                if (!il_light_sample_at(s, p, us, u, &ls))
                    continue;
                front++;
                float pa = il_light_pdf_area(s, ls.light, p, ls.p, ls.n);
                if (fabsf(pa - ls.pdf) > 1e-4f * ls.pdf)
                    mismatches++;
                CHECK(!ls.delta);
                /* Divide out the selection of the quad (two triangles). */
                inv_sum += (s->light_pmf[ls.light] / ls.pdf);
                n++;
            }
        CHECK(front == 256 * 64);
        CHECK(mismatches == 0);
        double omega = 4.0 * asin(1.0 * 0.5 / sqrt((1.0 + 4.0) * (0.25 + 4.0)));
        /* Each triangle's 1/pdf averages to its own solid angle; their sum is the quad's. */
        CHECK_REL(inv_sum / n * 2.0, omega, 0.01);

        /* From above, the one-sided emitter (facing down) shows its back: nothing. */
        il_light_sample ls;
        CHECK(!il_light_sample_at(s, v3(0, 3, 0), 0.5f * (lo + hi), v2(0.3f, 0.3f), &ls));
        /* The two-sided emitter shines on both sides. */
        float u2 = 0.5f * (s->light_cdf[6] + s->light_cdf[8]);
        CHECK(il_light_sample_at(s, v3(3, 1, 0), u2, v2(0.3f, 0.3f), &ls));
        CHECK(il_light_sample_at(s, v3(1, 1, 0), u2, v2(0.3f, 0.3f), &ls));
        CHECK_NEAR(ls.radiance.x, 1.0, 1e-7);
        /* Not an area light: no area pdf. */
        CHECK(il_light_pdf_area(s, 0, p, v3(0, 2, 0), v3(0, -1, 0)) == 0.0f);
    }

    /* Emission only from the front face unless two-sided. */
    {
        il_material m = {.emission = {1, 2, 3}};
        il_vec3 e = il_emitted_radiance(&m, v3(0, 1, 0), v3(0, 1, 0));
        CHECK(e.x == 1.0f && e.z == 3.0f);
        e = il_emitted_radiance(&m, v3(0, 1, 0), v3(0, -1, 0));
        CHECK(v3_is_zero(e));
        m.two_sided = true;
        e = il_emitted_radiance(&m, v3(0, 1, 0), v3(0, -1, 0));
        CHECK(e.y == 2.0f);
    }
    il_scene_release(s);

    /* Wide spots: with n > 0 the cos^n profile ends at 90 degrees; with n = 0
     * a 180 degree spot is a point light. */
    {
        il_scene *w = NULL;
        CHECK_OK(il_scene_create(&w, &err), &err);
        add_quad(w, v3(0, 0, 0), v3(1, 0, 0), v3(0, 0, -1), 0);
        il_light_desc wide = {.type = IL_LIGHT_SPOT, .position = {0, 1, 0}, .intensity = {1, 1, 1},
                              .spot_angle = 120, .spot_exponent = 1.5f};
        il_light_desc full = {.type = IL_LIGHT_SPOT, .position = {0, 1, 0}, .intensity = {1, 1, 1},
                              .spot_angle = 180};
        CHECK_OK(il_scene_add_light(w, &wide, &err), &err);
        CHECK_OK(il_scene_add_light(w, &full, &err), &err);
        CHECK_OK(il_scene_commit(w, &err), &err);
        CHECK(w->num_lights == 2);
        CHECK_REL(w->lights[0].power, 2.0 * PI_D / 2.5, 1e-5);
        CHECK_REL(w->lights[1].power, 4.0 * PI_D, 1e-5);
        il_light_sample ls;
        float u0 = 0.5f * w->light_cdf[1];
        double a = 60.0 * PI_D / 180.0;
        CHECK(il_light_sample_at(w, v3((float)sin(a), (float)(1.0 - cos(a)), 0), u0, v2(0.5f, 0.5f), &ls));
        CHECK_REL(ls.radiance.x, pow(cos(a), 1.5), 1e-4);
        a = 100.0 * PI_D / 180.0;
        CHECK(!il_light_sample_at(w, v3((float)sin(a), (float)(1.0 - cos(a)), 0), u0, v2(0.5f, 0.5f), &ls));
        float u1 = 0.5f * (w->light_cdf[1] + 1.0f);
        CHECK(il_light_sample_at(w, v3(0, 3, 0), u1, v2(0.5f, 0.5f), &ls));
        CHECK_REL(ls.radiance.y, 0.25, 1e-5);
        il_scene_release(w);
    }
    return check_report();
}
