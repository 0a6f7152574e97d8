/* il_measure_illuminance against analytic irradiance:
 * - a point light: E = I cos(theta) / d^2 (the inverse-square cosine law);
 * - a spot light: the same times its cos^n profile, zero outside its cone;
 * - a directional light: E = E0 cos(theta);
 * - a directional light with a disc (the sun's soft shadow): under the
 *   edge of a black half-plane, the fraction of the disc's irradiance
 *   that passes it, integrated over the disc by quadrature (the penumbra's
 *   profile, half at the edge);
 * - a square emitter of radiance L above the sensor: E = pi L F, F the
 *   point-to-parallel-rectangle form factor (Howell's catalogue, B-3:
 *   F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2)
 *   atan(X/sqrt(1+Y^2))] below a corner, X = a/h, Y = b/h);
 * - the furnace: inside a closed box whose walls emit Le and reflect rho,
 *   the radiance is Le/(1-rho) everywhere, so E = pi Le/(1-rho);
 * - the CIE overcast sky (il_sky_overcast) with its ground: E = the sky's
 *   horizontal illuminance facing up; facing sideways E_v / E_h =
 *   (pi/6 + 4/9) / (7 pi/9) + albedo / 2 (the sky's half of a vertical
 *   hemisphere, L = Lz (1 + 2 sin a)/3, integrates to Lz (pi/6 + 4/9));
 * - the CIE clear sky with its sun (il_scene_set_daylight): facing up, the
 *   sky's horizontal illuminance plus E_sun sin(altitude); facing the sun
 *   under a black sky, E_sun (the sun's direction, north turned);
 * and against the path tracer: on the Cornell box's floor, the floor's
 * radiance rho E / pi (Lambert).  Lux are 683 lm/W times the Rec.709
 * luminance.  Readings do not depend on the thread count; a stopped
 * measurement keeps the samples taken; the paths traced together as a wave
 * (il_pt_sensor_wave, what il_measure_illuminance runs) give the scalar
 * estimator's values bit for bit. */
#include "pt_scenes.h"
#include "methods/camera_wave.h"
#include "scene/scene.h"

static double luminance(il_vec3 e) { return 0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z; }

static il_scene *dark_floor_scene(void)
{
    il_scene *s = new_scene();
    uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0.0f)});
    add_floor(s, -10.0f, 20.0f, black);
    return s;
}

static void measure(const il_scene *s, const il_sensor *sn, size_t n, il_illuminance_desc d,
                    il_illuminance *out, il_illuminance_stats *st)
{
    CHECK_OK(il_measure_illuminance(s, sn, n, &d, out, st, &g_err), &g_err);
}

/* Every channel of a reading against the expected irradiance, and its lux. */
static void check_reading(const char *what, const il_illuminance *r, il_vec3 expect, double rel)
{
    printf("%s: E = (%.6g, %.6g, %.6g), expected (%.6g, %.6g, %.6g); %.6g lx +- %.3g\n", what,
           (double)r->irradiance.x, (double)r->irradiance.y, (double)r->irradiance.z,
           (double)expect.x, (double)expect.y, (double)expect.z, (double)r->lux,
           (double)r->lux_error);
    double abs_tol = 1e-6;
    CHECK_NEAR(r->irradiance.x, expect.x, rel * expect.x + abs_tol);
    CHECK_NEAR(r->irradiance.y, expect.y, rel * expect.y + abs_tol);
    CHECK_NEAR(r->irradiance.z, expect.z, rel * expect.z + abs_tol);
    CHECK_NEAR(r->lux, 683.0 * luminance(expect), rel * 683.0 * luminance(expect) + 1e-3);
}

static void test_point_and_spot(void)
{
    const il_vec3 I = v3(3.0f, 2.0f, 1.0f);
    il_scene *s = dark_floor_scene();
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 2, 0),
                                                    .intensity = I}, &g_err), &g_err);
    commit(s);
    const il_sensor sn[4] = {
        {v3(0, 0, 0), v3(0, 1, 0)},
        {v3(1.5f, 0, 0), v3(0, 3, 0)},           /* normals need not be unit */
        {v3(-1, 0, 0), v3(1, 1, 0)},             /* tilted towards the light */
        {v3(0, 0, 0), v3(0, -1, 0)},             /* facing away */
    };
    il_illuminance r[4];
    il_illuminance_stats st;
    measure(s, sn, 4, (il_illuminance_desc){.samples = 256, .seed = 1}, r, &st);
    CHECK(st.samples == 256 && st.nonfinite_samples == 0);
    check_reading("point, below", &r[0], v3_scale(I, 1.0f / 4.0f), 1e-4);
    /* d^2 = 2^2 + 1.5^2 = 6.25, cos = 2/2.5 */
    check_reading("point, 1.5 m aside", &r[1], v3_scale(I, 0.8f / 6.25f), 1e-4);
    /* to the light (1,2,0)/sqrt 5; normal (1,1,0)/sqrt 2: cos = 3/sqrt 10, d^2 = 5 */
    check_reading("point, tilted", &r[2], v3_scale(I, (float)(3.0 / sqrt(10.0) / 5.0)), 1e-4);
    check_reading("point, facing away", &r[3], v3s(0.0f), 0.0);
    CHECK(r[0].lux_error < 1e-3f * r[0].lux); /* one light, no bounce: every sample agrees */
    il_scene_release(s);

    s = dark_floor_scene();
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_SPOT, .position = v3(0, 2, 0),
                                                    .intensity = I, .spot_angle = 30.0f,
                                                    .spot_exponent = 2.0f}, &g_err), &g_err);
    commit(s);
    const il_sensor spot[2] = {{v3(0.5f, 0, 0), v3(0, 1, 0)}, {v3(2, 0, 0), v3(0, 1, 0)}};
    measure(s, spot, 2, (il_illuminance_desc){.samples = 64}, r, &st);
    double d2 = 4.25, cosa = 2.0 / sqrt(d2); /* 14 degrees off the axis; the sensor's cos too */
    check_reading("spot, inside the cone", &r[0], v3_scale(I, (float)(cosa * cosa * cosa / d2)), 1e-4);
    check_reading("spot, outside the cone", &r[1], v3s(0.0f), 0.0);
    il_scene_release(s);
}

static void test_directional(void)
{
    il_scene *s = dark_floor_scene();
    const il_vec3 E0 = v3(2.0f, 1.0f, 0.5f);
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_DIRECTIONAL,
                                                    .direction = v3(0, -1, -1), .intensity = E0},
                                &g_err), &g_err);
    commit(s);
    const il_sensor sn[2] = {{v3(0, 0, 0), v3(0, 1, 0)}, {v3(3, 1, 2), v3(0, 1, 1)}};
    il_illuminance r[2];
    measure(s, sn, 2, (il_illuminance_desc){.samples = 64}, r, NULL);
    check_reading("sun, horizontal sensor", &r[0], v3_scale(E0, (float)(1.0 / sqrt(2.0))), 1e-4);
    check_reading("sun, facing it", &r[1], E0, 1e-4);
    il_scene_release(s);
}

/* The irradiance at (x, 0, 0), facing up, from a disc of angular radius a
 * about the zenith and radiance E / (pi sin^2 a), past a black half-plane
 * x < 0 at height h: the blocked directions reach y = h at x + h tan < 0.
 * As a fraction of E, by the midpoint rule over the cap (cos-weighted). */
static double disc_fraction(double x, double h, double a)
{
    enum { NA = 600, NP = 1200 };
    double sum = 0.0;
    for (int i = 0; i < NA; i++) {
        double al = (i + 0.5) * a / NA, w = cos(al) * sin(al) * (a / NA) * (2.0 * PI_D / NP);
        for (int j = 0; j < NP; j++) {
            double ph = (j + 0.5) * 2.0 * PI_D / NP;
            if (x + h * sin(al) * cos(ph) / cos(al) >= 0.0)
                sum += w;
        }
    }
    return sum / (PI_D * sin(a) * sin(a));
}

static void test_disc_penumbra(void)
{
    const double h = 1.0, half = 5.0 * PI_D / 180.0, E0 = 100.0;
    il_scene *s = new_scene();
    uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0.0f)});
    add_quad(s, v3(-20, (float)h, 0), v3(20, 0, 0), v3(0, 0, -40), black); /* x in [-40, 0] */
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_DIRECTIONAL, .direction = v3(0, -1, 0),
                                                    .intensity = v3s((float)E0), .diameter = 10.0f},
                                &g_err), &g_err);
    commit(s);
    const double beta[] = {-7.0, -4.0, -2.5, -1.0, 0.0, 1.0, 2.5, 4.0, 7.0}; /* degrees off the edge */
    enum { K = sizeof beta / sizeof beta[0] };
    il_sensor sn[K];
    for (int k = 0; k < K; k++)
        sn[k] = (il_sensor){v3((float)(h * tan(beta[k] * PI_D / 180.0)), 0, 0), v3(0, 1, 0)};
    il_illuminance r[K];
    measure(s, sn, K, (il_illuminance_desc){.samples = 16384, .seed = 3}, r, NULL);
    for (int k = 0; k < K; k++) {
        double want = disc_fraction(sn[k].position.x, h, half), got = r[k].irradiance.x / E0;
        printf("penumbra at %+.1f deg: %.4f of the full sun (disc quadrature %.4f)\n", beta[k], got, want);
        CHECK_NEAR(got, want, 0.005);
    }
    CHECK(r[0].irradiance.x == 0.0f);
    CHECK_REL(r[K - 1].irradiance.x, E0, 1e-4);
    il_scene_release(s);
}

/* Howell B-3: a differential area below a corner of a parallel a x b
 * rectangle at height h. */
static double corner_ff(double a, double b, double h)
{
    double X = a / h, Y = b / h, sx = sqrt(1.0 + X * X), sy = sqrt(1.0 + Y * Y);
    return (X / sx * atan(Y / sx) + Y / sy * atan(X / sy)) / (2.0 * PI_D);
}

static void test_area_light(void)
{
    il_scene *s = dark_floor_scene();
    const il_vec3 L = v3(2.0f, 1.5f, 1.0f);
    uint32_t lamp = add_material(s, (il_material_desc){.diffuse = v3s(0.0f), .emission = L});
    /* A 1 m square at height 1, facing down (normal (0,-1,0)). */
    add_quad(s, v3(0, 1, 0), v3(0.5f, 0, 0), v3(0, 0, 0.5f), lamp);
    commit(s);
    const il_sensor sn[2] = {{v3(0, 0, 0), v3(0, 1, 0)}, {v3(0.5f, 0, 0), v3(0, 1, 0)}};
    il_illuminance r[2];
    il_illuminance_stats st;
    measure(s, sn, 2, (il_illuminance_desc){.samples = 4096, .seed = 7}, r, &st);
    double centre = 4.0 * corner_ff(0.5, 0.5, 1.0), edge = 2.0 * corner_ff(1.0, 0.5, 1.0);
    check_reading("square lamp, below its centre", &r[0], v3_scale(L, (float)(PI_D * centre)), 0.01);
    check_reading("square lamp, below an edge", &r[1], v3_scale(L, (float)(PI_D * edge)), 0.01);
    CHECK(r[0].lux_error > 0.0f && r[0].lux_error < 0.01f * r[0].lux);
    il_scene_release(s);
}

static il_scene *furnace_box(il_vec3 e, float rho)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = v3s(rho), .emission = e});
    add_cube(s, m, true);
    commit(s);
    return s;
}

static void test_furnace_and_threads(void)
{
    const il_vec3 e = v3(1.0f, 0.5f, 0.25f);
    const float rho = 0.5f;
    il_scene *s = furnace_box(e, rho);
    const il_sensor sn[3] = {
        {v3(0.2f, -0.3f, 0.1f), v3(0.3f, 0.8f, -0.5f)},
        {v3(0, -1, 0), v3(0, 1, 0)},             /* on the floor */
        {v3(0.9f, 0.9f, -0.9f), v3(-1, 0, 0)},   /* near a corner */
    };
    il_illuminance one[3], two[3];
    il_illuminance_desc d = {.samples = 2048, .max_depth = 64, .seed = 5, .threads = 1};
    measure(s, sn, 3, d, one, NULL);
    d.threads = 2;
    measure(s, sn, 3, d, two, NULL);
    il_vec3 expect = v3_scale(e, (float)(PI_D / (1.0 - rho)));
    for (int i = 0; i < 3; i++)
        check_reading("furnace", &one[i], expect, 0.01);
    CHECK(memcmp(one, two, sizeof one) == 0);
    il_scene_release(s);
}

/* The floor of the Cornell box: the path tracer's radiance towards a
 * point of it against rho E / pi from a sensor lying there. */
static void test_against_path_tracer(void)
{
    il_scene *s = load_committed("cornell");
    if (!s)
        return;
    const il_vec3 p = v3(0.08f, 0.0f, 0.5f), eye = v3(0.28f, 0.4f, 0.3f);
    il_ray ray = {.org = eye, .dir = v3_normalize(v3_sub(p, eye)), .tmax = INFINITY};
    il_hit hit;
    CHECK(il_trace_closest(s->tracer, &ray, &hit));
    il_surface surf;
    il_scene_surface(s, hit.mesh, hit.prim, hit.b1, hit.b2, &surf);
    CHECK_NEAR(surf.p.y, 0.0, 1e-4);
    il_sensor sn = {surf.p, surf.ng};
    il_illuminance r;
    measure(s, &sn, 1, (il_illuminance_desc){.samples = 16384, .seed = 11}, &r, NULL);

    const uint32_t n = 16384;
    double sum[3] = {0, 0, 0};
    uint64_t rays = 0;
    for (uint32_t k = 0; k < n; k++) {
        il_sampler smp;
        il_sampler_start(&smp, IL_SAMPLER_SOBOL, 11, 0, k);
        il_vec3 L = il_pt_radiance(s, eye, ray.dir, &smp, 8, IL_PT_MIS, &rays);
        sum[0] += L.x, sum[1] += L.y, sum[2] += L.z;
    }
    il_vec3 rho = surf.material->diffuse;
    il_vec3 expect = {(float)(sum[0] / n * PI_D / rho.x), (float)(sum[1] / n * PI_D / rho.y),
                      (float)(sum[2] / n * PI_D / rho.z)};
    /* Both at max depth 8: the floor is the camera path's first bounce as
     * the sensor is the sensor path's. */
    check_reading("Cornell floor against the path tracer (pi L / rho)", &r, expect, 0.02);
    il_scene_release(s);
}

/* Sensor paths of the Cornell box traced as one wave against the same
 * paths one at a time, with both samplers. */
static void test_wave_matches_scalar(void)
{
    il_scene *s = load_committed("cornell");
    if (!s)
        return;
    enum { N = 256 };
    static il_vec3 p[N], n[N], wave[N];
    static il_sampler smp[N];
    void *scratch = aligned_alloc(64, (il_pt_wavefront_scratch_bytes() + 63) / 64 * 64);
    CHECK(IL_PT_WAVE >= N);
    for (int type = 0; type < 2; type++) {
        for (uint32_t k = 0; k < N; k++) {
            /* 16 sensors in the box, some on the floor, facing all ways. */
            uint32_t i = k / 16;
            p[k] = v3(0.05f + 0.03f * i, i % 3 == 0 ? 0.0f : 0.1f + 0.02f * i, 0.5f - 0.025f * i);
            n[k] = v3_normalize(i % 3 == 0 ? v3(0, 1, 0) : v3(0.3f * (float)(i % 4) - 0.4f, 0.5f, -0.2f));
            il_sampler_start(&smp[k], type ? IL_SAMPLER_PCG : IL_SAMPLER_SOBOL, 9, i, k % 16);
        }
        uint64_t rays_wave = 0, rays_scalar = 0;
        il_pt_sensor_wave(s, 8, il_wave_wants_prefetch(s), scratch, p, n, smp, N, wave, &rays_wave);
        int same = 0;
        for (uint32_t k = 0; k < N; k++) {
            il_sampler one;
            il_sampler_start(&one, type ? IL_SAMPLER_PCG : IL_SAMPLER_SOBOL, 9, k / 16, k % 16);
            il_vec3 e = il_pt_sensor_irradiance(s, p[k], n[k], &one, 8, &rays_scalar);
            same += memcmp(&e, &wave[k], sizeof e) == 0;
        }
        printf("wave against scalar (%s): %d of %d paths identical, %llu and %llu rays\n",
               type ? "pcg" : "sobol", same, N, (unsigned long long)rays_wave,
               (unsigned long long)rays_scalar);
        CHECK(same == N && rays_wave == rays_scalar);
    }
    free(scratch);
    il_scene_release(s);
}

/* A named box, its faces outwards: a desk top of 2 x 0.05 x 1 m at y 0.7-0.75. */
static void add_desk(il_scene *s, uint32_t mat)
{
    const float lo[3] = {-1.0f, 0.7f, -0.5f}, hi[3] = {1.0f, 0.75f, 0.5f};
    float p[24 * 3];
    uint32_t idx[36];
    int nv = 0, ni = 0;
    for (int a = 0; a < 3; a++)
        for (int side = 0; side < 2; side++) {
            int b = (a + 1) % 3, c = (a + 2) % 3;
            float sign = side ? 1.0f : -1.0f;
            const float bc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int k = 0; k < 4; k++) {
                float q[3];
                q[a] = side ? hi[a] : lo[a];
                q[b] = bc[k][0] ? hi[b] : lo[b];
                q[c] = bc[k][1] ? hi[c] : lo[c];
                memcpy(p + 3 * (nv + k), q, sizeof q);
            }
            /* b x c is +a: counter-clockwise seen from +a keeps the order. */
            const uint32_t fwd[6] = {0, 1, 2, 0, 2, 3}, back[6] = {0, 2, 1, 0, 3, 2};
            for (int k = 0; k < 6; k++)
                idx[ni + k] = (uint32_t)nv + (sign > 0 ? fwd[k] : back[k]);
            nv += 4, ni += 6;
        }
    il_mesh_desc m = {.name = "Desk_Top", .num_vertices = 24, .num_triangles = 12, .positions = p,
                      .indices = idx, .material = mat};
    CHECK_OK(il_scene_add_mesh(s, &m, &g_err), &g_err);
}

/* il_surface_sensors on a desk: its top alone (facing +y) or every face,
 * found by mesh or material name; the mean reading over the top under a
 * point light 1 m above its centre against the exact area average
 * E = I Omega / A (every dA receives I cos / d^2 = I dOmega / dA, Omega the
 * solid angle the top subtends at the light: 4 asin(ab / sqrt((a^2 +
 * h^2)(b^2 + h^2))) for half-sides a, b at height h). */
static void test_surface_sensors(void)
{
    il_scene *s = new_scene();
    uint32_t oak = add_material(s, (il_material_desc){.name = "oak", .diffuse = v3s(0.0f)});
    add_desk(s, oak);
    uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0.0f)});
    add_floor(s, 0.0f, 3.0f, black);
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 1.75f, 0),
                                                    .intensity = v3s(10.0f)}, &g_err), &g_err);
    commit(s);

    il_surface_sensor_info info;
    il_surface_sensor_desc top = {.name = "desk", .facing = v3(0, 1, 0), .spacing = 0.1f};
    CHECK_OK(il_surface_sensors(s, &top, NULL, 0, &info, &g_err), &g_err);
    printf("desk top: %zu sensors, %llu triangles, %.4f m^2\n", info.count,
           (unsigned long long)info.triangles, info.area);
    CHECK(info.count == 200 && info.triangles == 2);
    CHECK_NEAR(info.area, 2.0, 1e-5);
    static il_sensor sn[500];
    static il_illuminance r[500];
    CHECK_OK(il_surface_sensors(s, &top, sn, 500, &info, &g_err), &g_err);
    bool on_top = true;
    for (size_t i = 0; i < info.count; i++)
        on_top = on_top && fabsf(sn[i].position.y - 0.75f) < 1e-5f && sn[i].normal.y > 0.9999f &&
                 fabsf(sn[i].position.x) <= 1.0f && fabsf(sn[i].position.z) <= 0.5f;
    CHECK(on_top);
    measure(s, sn, info.count, (il_illuminance_desc){.samples = 16, .max_depth = 1}, r, NULL);
    double sum = 0.0;
    for (size_t i = 0; i < info.count; i++)
        sum += r[i].irradiance.x;
    double a = 1.0, b = 0.5, h = 1.0;
    double omega = 4.0 * asin(a * b / sqrt((a * a + h * h) * (b * b + h * h)));
    printf("desk top under the lamp: mean %.5f W/m^2, area average I Omega / A = %.5f\n",
           sum / (double)info.count, 10.0 * omega / 2.0);
    CHECK_REL(sum / (double)info.count, 10.0 * omega / 2.0, 0.005);

    /* Every face, found by the material's name: 2 (2 x 1) + 2 (2 x 0.05) + 2 (1 x 0.05). */
    il_surface_sensor_desc all = {.name = "OAK", .spacing = 0.1f};
    CHECK_OK(il_surface_sensors(s, &all, sn, 500, &info, &g_err), &g_err);
    printf("every face: %zu sensors, %llu triangles, %.4f m^2\n", info.count,
           (unsigned long long)info.triangles, info.area);
    CHECK(info.count == 430 && info.triangles == 12);
    CHECK_NEAR(info.area, 4.3, 1e-4);
    int outward = 0;
    for (size_t i = 0; i < info.count; i++) {
        il_vec3 q = sn[i].position, n = sn[i].normal, c = v3(0, 0.725f, 0);
        outward += v3_dot(n, v3_sub(q, c)) > 0.0f && fabsf(v3_length(n) - 1.0f) < 1e-5f;
    }
    CHECK(outward == 430);

    il_error err = {0};
    il_surface_sensor_desc none = {.name = "walnut"};
    CHECK(il_surface_sensors(s, &none, NULL, 0, &info, &err) == IL_ERR_INVALID);
    printf("no match: %s\n", err.message);
    CHECK(strstr(err.message, "'Desk_Top'") != NULL);
    il_surface_sensor_desc sideways = {.name = "desk", .facing = v3(1, 1, 1)}; /* 54.7 degrees from each face */
    CHECK(il_surface_sensors(s, &sideways, NULL, 0, &info, &err) == IL_ERR_INVALID);
    printf("no face that way: %s\n", err.message);
    il_scene_release(s);
}

static bool stop_at_once(double fraction, double seconds, void *user)
{
    (void)fraction, (void)seconds;
    ++*(int *)user;
    return false;
}

static void test_stop_and_bad_input(void)
{
    il_scene *s = dark_floor_scene();
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 2, 0),
                                                    .intensity = v3s(1.0f)}, &g_err), &g_err);
    commit(s);
    il_sensor sn = {v3(0, 0, 0), v3(0, 1, 0)};
    il_illuminance r;
    il_illuminance_stats st;
    int calls = 0;
    measure(s, &sn, 1, (il_illuminance_desc){.samples = 1u << 18, .progress = stop_at_once,
                                             .progress_user = &calls}, &r, &st);
    printf("stopped after %d progress call(s): %u samples\n", calls, st.samples);
    CHECK(calls == 1 && st.samples > 0 && st.samples < (1u << 18) && st.samples % 64 == 0);
    CHECK_REL(r.irradiance.x, 0.25, 1e-4);

    const il_sensor bad[3] = {{v3(NAN, 0, 0), v3(0, 1, 0)}, {v3(0, 0, 0), v3(0, 0, 0)},
                              {v3(0, 0, 0), v3(0, INFINITY, 0)}};
    for (int i = 0; i < 3; i++) {
        il_error err = {0};
        il_illuminance_desc d = {.samples = 4};
        CHECK(il_measure_illuminance(s, &bad[i], 1, &d, &r, NULL, &err) == IL_ERR_INVALID);
        printf("bad sensor %d: %s\n", i, err.message);
    }
    il_error err = {0};
    il_illuminance_desc many = {.samples = (1u << 30) + 1};
    CHECK(il_measure_illuminance(s, &sn, 1, &many, &r, NULL, &err) == IL_ERR_INVALID);
    CHECK(il_measure_illuminance(s, NULL, 1, &many, &r, NULL, &err) == IL_ERR_INVALID);
    il_scene_release(s);

    il_scene *open = dark_floor_scene(); /* never committed */
    il_illuminance_desc d = {.samples = 4};
    CHECK(il_measure_illuminance(open, &sn, 1, &d, &r, NULL, &err) == IL_ERR_INVALID);
    il_scene_release(open);
}

/* il_camera_sensors: looking down at the floor, every pixel sees it, its
 * sensors lie on it and face up; looking up, no pixel sees anything. */
static void test_camera_sensors(void)
{
    il_scene *s = dark_floor_scene();
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 2, 0),
                                                    .intensity = v3s(1.0f)}, &g_err), &g_err);
    set_camera(s, v3(0, 0, 0), v3(0, -1, 0), v3(0, 0, -1), 40.0f);
    commit(s);
    enum { W = 9, H = 7 };
    il_sensor sn[W * H];
    bool seen[W * H];
    CHECK_OK(il_camera_sensors(s, W, H, sn, seen, &g_err), &g_err);
    int on_floor = 0;
    for (int i = 0; i < W * H; i++)
        on_floor += seen[i] && fabsf(sn[i].position.y + 10.0f) < 1e-3f && sn[i].normal.y > 0.999f;
    CHECK(on_floor == W * H);
    /* The centre pixel looks straight down. */
    CHECK_NEAR(sn[(H / 2) * W + W / 2].position.x, 0.0, 1e-4);
    CHECK_NEAR(sn[(H / 2) * W + W / 2].position.z, 0.0, 1e-4);
    set_camera(s, v3(0, 0, 0), v3(0, 1, 0), v3(0, 0, -1), 40.0f);
    CHECK_OK(il_camera_sensors(s, W, H, sn, seen, &g_err), &g_err);
    int any = 0;
    for (int i = 0; i < W * H; i++)
        any += seen[i];
    CHECK(any == 0);
    il_error err = {0};
    CHECK(il_camera_sensors(s, 0, H, sn, seen, &err) == IL_ERR_INVALID);
    il_scene_release(s);
}

/* A sensor under the open overcast sky, the scene's own lights removed
 * (il_scene_remove_lights) and nothing else in view but a speck. */
static void test_overcast_sky(void)
{
    il_scene *s = new_scene();
    uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0.0f)});
    uint32_t lamp = add_material(s, (il_material_desc){.emission = v3s(100.0f)});
    add_quad(s, v3(500, 500, 500), v3(0.01f, 0, 0), v3(0, 0.01f, 0), black);
    add_quad(s, v3(0, 1, 0), v3(0.5f, 0, 0), v3(0, 0, 0.5f), lamp);
    CHECK_OK(il_scene_add_light(s, &(il_light_desc){.type = IL_LIGHT_POINT, .position = v3(0, 2, 0),
                                                    .intensity = v3s(50.0f)}, &g_err), &g_err);
    CHECK_OK(il_scene_remove_lights(s, &g_err), &g_err);
    il_image sky = {0};
    CHECK_OK(il_sky_overcast(&(il_sky_desc){.horizontal_lux = 10000.0}, &sky, &g_err), &g_err);
    CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.map = &sky}, &g_err), &g_err);
    il_image_free(&sky);
    commit(s);
    const il_sensor sn[2] = {{v3(3, 0, 0), v3(0, 1, 0)}, {v3(3, 0, 0), v3(1, 0, 0)}};
    il_illuminance r[2];
    measure(s, sn, 2, (il_illuminance_desc){.samples = 4096, .seed = 3}, r, NULL);
    double vertical = (PI_D / 6.0 + 4.0 / 9.0) / (7.0 * PI_D / 9.0) + 0.2 / 2.0;
    printf("overcast: horizontal %.1f lx (expected 10000), vertical %.1f lx (expected %.1f)\n",
           (double)r[0].lux, (double)r[1].lux, 10000.0 * vertical);
    CHECK_REL(r[0].lux, 10000.0, 0.01);
    CHECK_REL(r[1].lux, 10000.0 * vertical, 0.01);
    il_error err = {0};
    CHECK(il_scene_remove_lights(s, &err) == IL_ERR_INVALID); /* committed */
    il_scene_release(s);

    /* Without the sky nothing is left to light it. */
    s = new_scene();
    lamp = add_material(s, (il_material_desc){.emission = v3s(1.0f)});
    add_floor(s, 0.0f, 1.0f, lamp);
    CHECK_OK(il_scene_remove_lights(s, &g_err), &g_err);
    CHECK(il_scene_commit(s, &err) == IL_ERR_INVALID);
    printf("no light left: %s\n", err.message);
    il_scene_release(s);
}

/* The clear sky and its sun (il_scene_set_daylight): an upward sensor gets
 * the sky's horizontal illuminance plus E_sun sin(altitude); a sensor facing
 * the sun under a nearly black sky gets E_sun, and one facing away none of it. */
static void test_cie_sky_and_sun(void)
{
    const double alt = 35.0, sun = 60000.0;
    for (int facing = 0; facing < 2; facing++) {
        il_scene *s = new_scene();
        uint32_t black = add_material(s, (il_material_desc){.diffuse = v3s(0.0f)});
        add_quad(s, v3(500, 500, 500), v3(0.01f, 0, 0), v3(0, 0.01f, 0), black);
        il_sky_desc d = {.cie_type = 12, .sun_altitude = alt, .sun_azimuth = 200.0, .north = 30.0,
                         .sun_normal_lux = sun, .horizontal_lux = facing ? 1e-3 : 15000.0,
                         .ground_albedo = facing ? -1.0 : 0.0};
        CHECK_OK(il_scene_set_daylight(s, &d, &g_err), &g_err);
        /* il_scene_get_daylight gives the sky back as set, defaults filled
         * in; switching the lamps off keeps it. */
        il_sky_desc got;
        CHECK_OK(il_scene_remove_lights(s, &g_err), &g_err);
        CHECK(il_scene_get_daylight(s, &got));
        CHECK(got.cie_type == 12 && got.sun_altitude == alt && got.sun_azimuth == 200.0 && got.north == 30.0);
        CHECK(got.sun_normal_lux == sun && got.horizontal_lux == d.horizontal_lux && got.width == 256u);
        CHECK(got.ground_albedo == (facing ? -1.0 : 0.2));
        commit(s);
        CHECK(il_scene_get_daylight(s, NULL));
        /* Azimuth 200 with north turned 30: 170 degrees clockwise from -z. */
        double a = 170.0 * PI_D / 180.0, h = alt * PI_D / 180.0;
        il_vec3 to_sun = v3((float)(cos(h) * sin(a)), (float)sin(h), (float)(-cos(h) * cos(a)));
        il_sensor sn[2] = {{v3(0, 0, 0), v3(0, 1, 0)}, {v3(0, 0, 0), to_sun}};
        if (facing)
            sn[0].normal = v3(-to_sun.x, -to_sun.y, -to_sun.z);
        il_illuminance r[2];
        measure(s, sn, 2, (il_illuminance_desc){.samples = 4096, .seed = 5}, r, NULL);
        if (!facing) {
            double want = 15000.0 + sun * sin(h);
            printf("clear sky + sun: horizontal %.1f lx (expected %.1f)\n", (double)r[0].lux, want);
            CHECK_REL(r[0].lux, want, 0.01);
        } else {
            printf("sun alone: facing it %.2f lx (expected %.0f), facing away %.4f lx\n", (double)r[1].lux,
                   sun, (double)r[0].lux);
            CHECK_REL(r[1].lux, sun, 1e-4);
            CHECK(r[0].lux < 1e-2);
        }
        il_scene_release(s);
    }
    /* The overcast sky through the same call has no sun. */
    il_scene *s = new_scene();
    il_error err = {0};
    CHECK(il_scene_set_daylight(s, &(il_sky_desc){.sun_normal_lux = 100.0}, &err) == IL_ERR_INVALID);
    CHECK(il_scene_set_daylight(s, NULL, &err) == IL_ERR_INVALID);
    CHECK(!il_scene_get_daylight(s, NULL) && !il_scene_get_daylight(NULL, NULL));
    /* An overcast sky, then a uniform environment in its place: no
     * daylight sky any more. */
    il_sky_desc got = {0};
    CHECK_OK(il_scene_set_daylight(s, &(il_sky_desc){.horizontal_lux = 5000.0}, &g_err), &g_err);
    CHECK(il_scene_get_daylight(s, &got) && got.cie_type == 0 && got.horizontal_lux == 5000.0 &&
          got.ground_albedo == 0.2);
    CHECK_OK(il_scene_set_environment(s, &(il_environment_desc){.radiance = v3s(1.0f)}, &g_err), &g_err);
    CHECK(!il_scene_get_daylight(s, &got));
    il_scene_release(s);
}

int main(void)
{
    test_overcast_sky();
    test_cie_sky_and_sun();
    test_camera_sensors();
    test_point_and_spot();
    test_directional();
    test_disc_penumbra();
    test_area_light();
    test_furnace_and_threads();
    test_against_path_tracer();
    test_wave_matches_scalar();
    test_surface_sensors();
    test_stop_and_bad_input();
    return check_report();
}
