/* Environment-map mappings (src/image/envmap.c): direction -> texel ->
 * direction round trips for lat-long, angular and cross; the angular map
 * against Debevec's formula worked by hand; where each axis lands; the
 * cross's folding (continuity across the cube edges it keeps); bilinear
 * lookups at texel centres and no bleeding across the cross's empty cells;
 * the Jacobians integrate to 4 pi; rotation; validation of bad images. */
#include <string.h>

#include "check.h"
#include "core/vec.h"
#include "image/envmap.h"

#define PI_D 3.14159265358979323846
static const il_env_mapping all_mappings[3] = {IL_ENV_LATLONG, IL_ENV_ANGULAR, IL_ENV_CROSS};

/* The i-th of n directions spread evenly over the sphere (Fibonacci lattice). */
static il_vec3 fib_dir(int i, int n)
{
    double z = 1.0 - (2.0 * i + 1.0) / n;
    double r = sqrt(fmax(0.0, 1.0 - z * z));
    double phi = i * PI_D * (3.0 - sqrt(5.0));
    return v3((float)(r * cos(phi)), (float)z, (float)(r * sin(phi)));
}

static double angle_between(il_vec3 a, il_vec3 b)
{
    return atan2(v3_length(v3_cross(a, b)), v3_dot(a, b));
}

static void check_uv(il_env_mapping m, il_vec3 d, double u, double v, double tol)
{
    il_vec2 uv = il_envmap_dir_to_uv(m, v3_normalize(d));
    if ((u >= 0.0 && fabs(uv.x - u) > tol) || fabs(uv.y - v) > tol)
        fprintf(stderr, "%s: dir (%g %g %g) -> uv (%g %g), expected (%g %g)\n",
                il_envmap_mapping_name(m), d.x, d.y, d.z, uv.x, uv.y, u, v);
    if (u >= 0.0)   /* u < 0: any u (a pole) */
        CHECK_NEAR(uv.x, u, tol);
    CHECK_NEAR(uv.y, v, tol);
}

static void test_round_trips(void)
{
    const int n = 20000;
    for (int k = 0; k < 3; k++) {
        il_env_mapping m = all_mappings[k];
        double worst = 0.0;
        for (int i = 0; i < n; i++) {
            il_vec3 d = fib_dir(i, n);
            il_vec3 back;
            bool ok = il_envmap_uv_to_dir(m, il_envmap_dir_to_uv(m, d), &back);
            CHECK(ok);
            if (ok)
                worst = fmax(worst, angle_between(d, back));
        }
        printf("%s: dir -> uv -> dir worst error %.3g rad over %d directions\n",
               il_envmap_mapping_name(m), worst, n);
        /* Float precision: the angular map loses a little near -z, where
         * the whole rim is one direction (radius error ~1e-7 there is an
         * angle error of pi * 1e-7 / sin). */
        CHECK(worst < 2e-4);

        /* uv -> dir -> uv at the texel centres of a 64-texel-wide map. */
        uint32_t w = 64, h = m == IL_ENV_LATLONG ? 32 : (m == IL_ENV_ANGULAR ? 64 : 64 / 3 * 4);
        if (m == IL_ENV_CROSS)
            w = 63;
        double worst_uv = 0.0;
        int inside = 0;
        for (uint32_t y = 0; y < h; y++)
            for (uint32_t x = 0; x < w; x++) {
                il_vec2 uv = v2((x + 0.5f) / w, (y + 0.5f) / h);
                il_vec3 d;
                if (!il_envmap_uv_to_dir(m, uv, &d))
                    continue;
                inside++;
                il_vec2 back = il_envmap_dir_to_uv(m, d);
                worst_uv = fmax(worst_uv, fmax(fabs(back.x - uv.x) * w, fabs(back.y - uv.y) * h));
            }
        printf("%s: texel centre -> dir -> texel worst error %.3g texels (%d texels hold sky)\n",
               il_envmap_mapping_name(m), worst_uv, inside);
        CHECK(worst_uv < 1e-3);
        /* The sky covers the whole lat-long image, pi/4 of the angular
         * map's square (the disk), half of the cross's 12 cells. */
        if (m == IL_ENV_LATLONG)
            CHECK(inside == (int)(w * h));
        else if (m == IL_ENV_ANGULAR)
            CHECK_REL(inside, PI_D / 4.0 * w * h, 0.02);
        else
            CHECK(inside == (int)(w * h / 2));
    }
}

static void test_hand_values(void)
{
    const double t = 1e-6;
    /* Angular, (a, b) = (Dx, Dy) acos(Dz) / (pi sqrt(Dx^2 + Dy^2)),
     * u = (a + 1)/2, v = (1 - b)/2. */
    check_uv(IL_ENV_ANGULAR, v3(0, 0, 1), 0.5, 0.5, t);            /* centre: a = b = 0 */
    check_uv(IL_ENV_ANGULAR, v3(1, 0, 0), 0.75, 0.5, t);           /* acos 0 = pi/2: a = 1/2 */
    check_uv(IL_ENV_ANGULAR, v3(-1, 0, 0), 0.25, 0.5, t);
    check_uv(IL_ENV_ANGULAR, v3(0, 1, 0), 0.5, 0.25, t);           /* b = 1/2 is up */
    check_uv(IL_ENV_ANGULAR, v3(1, 0, 1), 0.625, 0.5, t);          /* acos(1/sqrt2) = pi/4: a = 1/4 */
    /* 60 degrees from +z towards -y: a = 0, b = -1/3. */
    check_uv(IL_ENV_ANGULAR, v3(0, -sinf(IL_PI / 3), cosf(IL_PI / 3)), 0.5, 2.0 / 3.0, t);
    /* 135 degrees from +z in the direction (1, 1)/sqrt2 of the image:
     * r = 3/4, a = b = 3/(4 sqrt 2). */
    {
        float s = sinf(0.75f * IL_PI) / sqrtf(2.0f);
        double ab = 0.75 / sqrt(2.0);
        check_uv(IL_ENV_ANGULAR, v3(s, s, cosf(0.75f * IL_PI)), 0.5 * (ab + 1), 0.5 * (1 - ab), t);
    }
    /* Just off -z towards +x: on the rim, at the right. */
    check_uv(IL_ENV_ANGULAR, v3(1e-4f, 0, -1), 1.0, 0.5, 1e-4);

    /* Lat-long: centre column -z, +x at 3/4, -x at 1/4, +y top, -y bottom. */
    check_uv(IL_ENV_LATLONG, v3(0, 0, -1), 0.5, 0.5, t);
    check_uv(IL_ENV_LATLONG, v3(1, 0, 0), 0.75, 0.5, t);
    check_uv(IL_ENV_LATLONG, v3(-1, 0, 0), 0.25, 0.5, t);
    check_uv(IL_ENV_LATLONG, v3(0, 1, 0), -1.0, 0.0, t);        /* the poles: any u */
    check_uv(IL_ENV_LATLONG, v3(0, -1, 0), -1.0, 1.0, t);
    check_uv(IL_ENV_LATLONG, v3(1, 1, 0), 0.75, 0.25, t);          /* 45 degrees up */
    il_vec2 back = il_envmap_dir_to_uv(IL_ENV_LATLONG, v3(0, 0, 1)); /* the seam */
    CHECK(fabsf(back.x) < 1e-6f || fabsf(back.x - 1.0f) < 1e-6f);

    /* Cross: face centres. */
    check_uv(IL_ENV_CROSS, v3(0, 0, -1), 1.5 / 3, 1.5 / 4, t);
    check_uv(IL_ENV_CROSS, v3(1, 0, 0), 2.5 / 3, 1.5 / 4, t);
    check_uv(IL_ENV_CROSS, v3(-1, 0, 0), 0.5 / 3, 1.5 / 4, t);
    check_uv(IL_ENV_CROSS, v3(0, 1, 0), 1.5 / 3, 0.5 / 4, t);
    check_uv(IL_ENV_CROSS, v3(0, -1, 0), 1.5 / 3, 2.5 / 4, t);
    check_uv(IL_ENV_CROSS, v3(0, 0, 1), 1.5 / 3, 3.5 / 4, t);
    /* Within the front face: +x is to the right, +y up. */
    check_uv(IL_ENV_CROSS, v3(0.5f, 0, -1), (1 + 0.75) / 3, 1.5 / 4, t);
    check_uv(IL_ENV_CROSS, v3(0, 0.5f, -1), 1.5 / 3, (1 + 0.25) / 4, t);
    /* The back face hangs upside down: +y is towards the bottom of its cell. */
    check_uv(IL_ENV_CROSS, v3(0, 0.5f, 1), 1.5 / 3, (3 + 0.75) / 4, t);
}

/* Two directions on either side of a cube edge land next to each other in
 * the cross when the cross keeps that edge. */
static void check_edge(il_vec3 a, il_vec3 b, const char *what)
{
    il_vec2 ua = il_envmap_dir_to_uv(IL_ENV_CROSS, v3_normalize(a));
    il_vec2 ub = il_envmap_dir_to_uv(IL_ENV_CROSS, v3_normalize(b));
    double du = (ua.x - ub.x) * 3, dv = (ua.y - ub.y) * 4;   /* in face widths */
    double dist = sqrt(du * du + dv * dv);
    if (dist > 0.02)
        fprintf(stderr, "cross edge %s: %g face widths apart\n", what, dist);
    CHECK(dist < 0.02);
}

static void test_cross_folds(void)
{
    const float e = 0.999f;
    check_edge(v3(0.3f, 1, -e), v3(0.3f, e, -1), "top/front");
    check_edge(v3(0.3f, -1, -e), v3(0.3f, -e, -1), "bottom/front");
    check_edge(v3(1, 0.3f, -e), v3(e, 0.3f, -1), "right/front");
    check_edge(v3(-1, 0.3f, -e), v3(-e, 0.3f, -1), "left/front");
    check_edge(v3(0.3f, -1, e), v3(0.3f, -e, 1), "bottom/back");
}

/* A map whose texel (x, y) holds (x, y, 1 + x + y w). */
static il_image index_map(uint32_t w, uint32_t h)
{
    il_image img = {0};
    il_error err;
    CHECK_OK(il_image_alloc(&img, w, h, &err), &err);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            float *p = img.rgb + 3 * ((size_t)y * w + x);
            p[0] = (float)x;
            p[1] = (float)y;
            p[2] = 1.0f + x + (float)y * w;
        }
    return img;
}

static void test_lookups(void)
{
    /* At a texel centre the bilinear lookup is that texel. */
    for (int k = 0; k < 3; k++) {
        il_env_mapping m = all_mappings[k];
        uint32_t w = m == IL_ENV_CROSS ? 24 : 32, h = m == IL_ENV_LATLONG ? 16 : (m == IL_ENV_ANGULAR ? 32 : 32);
        il_image img = index_map(w, h);
        int bad = 0, n = 0;
        for (uint32_t y = 0; y < h; y++)
            for (uint32_t x = 0; x < w; x++) {
                il_vec3 d;
                if (!il_envmap_uv_to_dir(m, v2((x + 0.5f) / w, (y + 0.5f) / h), &d))
                    continue;
                il_vec3 L = il_envmap_lookup(&img, m, d);
                n++;
                if (fabsf(L.x - x) > 1e-3f || fabsf(L.y - y) > 1e-3f)
                    bad++;
            }
        printf("%s: %d of %d texel centres looked up exactly\n", il_envmap_mapping_name(m), n - bad, n);
        CHECK(bad == 0 && n > 0);
        il_image_free(&img);
    }

    /* Lat-long wraps: halfway between the last and the first column. */
    {
        il_image img = index_map(8, 4);
        il_vec3 d;
        il_envmap_uv_to_dir(IL_ENV_LATLONG, v2(0.0f, 1.5f / 4), &d);
        il_vec3 L = il_envmap_lookup(&img, IL_ENV_LATLONG, d);
        CHECK_NEAR(L.x, 3.5, 1e-4);   /* (7 + 0) / 2 */
        il_image_free(&img);
    }

    /* The cross never reads an empty cell: fill them with 1e6, the faces
     * with a smooth ramp in [1, 2]. */
    {
        uint32_t f = 16, w = 3 * f, h = 4 * f;
        il_image img = {0};
        il_error err;
        CHECK_OK(il_image_alloc(&img, w, h, &err), &err);
        for (uint32_t y = 0; y < h; y++)
            for (uint32_t x = 0; x < w; x++) {
                il_vec3 d;
                bool sky = il_envmap_uv_to_dir(IL_ENV_CROSS, v2((x + 0.5f) / w, (y + 0.5f) / h), &d);
                float v = sky ? 1.5f + 0.5f * d.y : 1e6f;
                float *p = img.rgb + 3 * ((size_t)y * w + x);
                p[0] = p[1] = p[2] = v;
            }
        float worst = 0.0f;
        for (int i = 0; i < 20000; i++) {
            il_vec3 d = fib_dir(i, 20000);
            il_vec3 L = il_envmap_lookup(&img, IL_ENV_CROSS, d);
            worst = il_maxf(worst, L.x);
        }
        printf("cross: largest lookup %g with 1e6 in the empty cells\n", worst);
        CHECK(worst <= 2.0f);
        il_image_free(&img);
    }
}

/* int dOmega = int J(u, v) du dv = 4 pi for each mapping (midpoint rule). */
static void test_jacobians(void)
{
    const int n = 1200;
    for (int k = 0; k < 3; k++) {
        double sum = 0.0;
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
                sum += il_envmap_jacobian(all_mappings[k], v2((x + 0.5f) / n, (y + 0.5f) / n));
        sum /= (double)n * n;
        printf("%s: integral of the Jacobian %.6f (4 pi = %.6f)\n", il_envmap_mapping_name(all_mappings[k]),
               sum, 4 * PI_D);
        CHECK_REL(sum, 4 * PI_D, 2e-3);
    }
    /* Against finite differences of uv_to_dir: the area of the image of a
     * small square is J du dv. */
    for (int k = 0; k < 3; k++) {
        il_env_mapping m = all_mappings[k];
        const il_vec2 pts[3] = {{0.3f, 0.4f}, {0.55f, 0.35f}, {0.45f, 0.6f}};
        for (int i = 0; i < 3; i++) {
            float h = 1e-3f;
            il_vec3 d0 = v3s(0), dx = v3s(0), dy = v3s(0);
            il_vec2 p = pts[i];
            if (m == IL_ENV_CROSS)   /* inside the front face */
                p = v2(0.4f + 0.1f * i, 0.3f + 0.05f * i);
            bool ok = il_envmap_uv_to_dir(m, p, &d0) && il_envmap_uv_to_dir(m, v2(p.x + h, p.y), &dx) &&
                      il_envmap_uv_to_dir(m, v2(p.x, p.y + h), &dy);
            CHECK(ok);
            double area = v3_length(v3_cross(v3_sub(dx, d0), v3_sub(dy, d0))) / ((double)h * h);
            CHECK_REL(il_envmap_jacobian(m, p), area, 5e-3);
        }
    }
}

static void test_rotation(void)
{
    /* A black lat-long map with one bright texel at local +x. */
    uint32_t w = 64, h = 32;
    il_image img = {0};
    il_error err;
    CHECK_OK(il_image_alloc(&img, w, h, &err), &err);
    il_vec2 uv = il_envmap_dir_to_uv(IL_ENV_LATLONG, v3(1, 0, 0));
    uint32_t sx = (uint32_t)(uv.x * w), sy = (uint32_t)(uv.y * h);
    for (int c = 0; c < 3; c++)
        img.rgb[3 * ((size_t)sy * w + sx) + c] = 100.0f;
    il_vec3 texel_dir;
    il_envmap_uv_to_dir(IL_ENV_LATLONG, v2((sx + 0.5f) / w, (sy + 0.5f) / h), &texel_dir);

    il_envmap env;
    CHECK_OK(il_envmap_init(&env, &img, IL_ENV_LATLONG, 0.0f, 0.0f, NULL, &err), &err);
    CHECK_NEAR(il_envmap_eval(&env, texel_dir).x, 100.0, 1e-3);
    il_envmap_free(&env);

    /* Turned 90 degrees counter-clockwise seen from above (+y): +x goes to
     * -z (looking down, x to the right, -z is up the page). */
    CHECK_OK(il_envmap_init(&env, &img, IL_ENV_LATLONG, 90.0f, 2.0f, NULL, &err), &err);
    il_vec3 turned = v3(texel_dir.z, texel_dir.y, -texel_dir.x);
    CHECK_NEAR(il_envmap_eval(&env, turned).x, 200.0, 1e-2);   /* intensity 2 */
    CHECK_NEAR(il_envmap_eval(&env, texel_dir).x, 0.0, 1e-6);
    /* to_world and to_local are inverse, and to_world turns +x to -z. */
    il_vec3 wx = il_envmap_to_world(&env, v3(1, 0, 0));
    CHECK_NEAR(wx.x, 0, 1e-6);
    CHECK_NEAR(wx.z, -1, 1e-6);
    for (int i = 0; i < 100; i++) {
        il_vec3 d = fib_dir(i, 100);
        CHECK(angle_between(il_envmap_to_local(&env, il_envmap_to_world(&env, d)), d) < 1e-6);
    }
    /* Samples cluster at the turned spot. */
    int near = 0;
    for (int i = 0; i < 1000; i++) {
        il_vec3 d;
        float pdf;
        il_envmap_sample(&env, v2((i + 0.5f) / 1000, fmodf(i * 0.618034f, 1.0f)), &d, &pdf);
        near += angle_between(d, turned) < 0.2;
    }
    printf("rotation: %d of 1000 samples within 0.2 rad of the turned spot\n", near);
    CHECK(near > 900);
    il_envmap_free(&env);
    il_image_free(&img);
}

static void test_validation(void)
{
    il_error err = {0};
    il_image img = {0};
    il_envmap env;
    CHECK_OK(il_image_alloc(&img, 40, 30, &err), &err);
    CHECK(il_envmap_init(&env, &img, IL_ENV_ANGULAR, 0, 0, NULL, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "square") != NULL);
    CHECK(il_envmap_init(&env, &img, IL_ENV_CROSS, 0, 0, NULL, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "3:4") != NULL);
    il_image_free(&img);

    CHECK_OK(il_image_alloc(&img, 8, 4, &err), &err);
    img.rgb[7] = NAN;
    CHECK(il_envmap_init(&env, &img, IL_ENV_LATLONG, 0, 0, NULL, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "NaN") != NULL);
    img.rgb[7] = INFINITY;
    CHECK(il_envmap_init(&env, &img, IL_ENV_LATLONG, 0, 0, NULL, &err) == IL_ERR_INVALID);
    img.rgb[7] = -2.0f;
    img.rgb[8] = 1.0f;
    uint64_t clamped = 0;
    CHECK_OK(il_envmap_init(&env, &img, IL_ENV_LATLONG, 0, 0, &clamped, &err), &err);
    CHECK(clamped == 1);
    CHECK(env.img.rgb[7] == 0.0f);
    il_envmap_free(&env);
    CHECK(il_envmap_init(&env, &img, IL_ENV_LATLONG, 0, -1.0f, NULL, &err) == IL_ERR_INVALID);
    CHECK(il_envmap_init(&env, &img, IL_ENV_LATLONG, NAN, 1.0f, NULL, &err) == IL_ERR_INVALID);
    CHECK(il_envmap_init(&env, NULL, IL_ENV_LATLONG, 0, 1.0f, NULL, &err) == IL_ERR_INVALID);

    /* Guessing the mapping from the size. */
    CHECK(il_envmap_mapping_for_size(512, 256) == IL_ENV_LATLONG);
    CHECK(il_envmap_mapping_for_size(256, 256) == IL_ENV_ANGULAR);
    CHECK(il_envmap_mapping_for_size(192, 256) == IL_ENV_CROSS);
    CHECK(il_envmap_mapping_for_size(300, 100) == IL_ENV_LATLONG);
    il_env_mapping m;
    CHECK(il_envmap_mapping_from_name("cross", &m) && m == IL_ENV_CROSS);
    CHECK(!il_envmap_mapping_from_name("cube", &m));

    /* Through the scene: a bad map is refused, a good one counts as an environment. */
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    il_environment_desc ed = {.map = &img, .mapping = IL_ENV_ANGULAR};
    CHECK(il_scene_set_environment(s, &ed, &err) == IL_ERR_INVALID);
    ed.mapping = IL_ENV_LATLONG;
    CHECK_OK(il_scene_set_environment(s, &ed, &err), &err);
    il_scene_info info;
    il_scene_get_info(s, &info);
    CHECK(info.has_environment);
    CHECK(info.num_warnings == 1);   /* the clamped texel */
    il_scene_release(s);
    il_image_free(&img);
}

int main(void)
{
    test_round_trips();
    test_hand_values();
    test_cross_folds();
    test_lookups();
    test_jacobians();
    test_rotation();
    test_validation();
    return check_report();
}
