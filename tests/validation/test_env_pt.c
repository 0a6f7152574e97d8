/* The path tracer under real environment maps (the shared Grace Cathedral
 * lat-long map and the Poly Haven map with a sun 69,000 times its mean).
 *
 * A diffuse plane of albedo rho with normal n, alone under the sky, sees
 * the sky over the hemisphere about n and nothing else, so its radiance is
 *   L_o = rho/pi * E,  E = int L(w) max(0, w.n) dOmega
 * everywhere on it.  E is integrated numerically from the map: over the
 * map's own (u, v) square, dOmega = 2 pi^2 sin(theta) du dv, with 4 x 4
 * midpoints per texel (exact for the bilinear lookup's linear pieces, so
 * even one-texel highlights are integrated right), each direction turned to
 * the world by our own rotation formula.  NEE + MIS (and light sampling
 * alone) must reproduce it within the
 * noise of the estimate, whose standard error is measured from the pixels
 * (the plane's radiance is the same in every pixel).
 *
 * Camera rays that escape show the sky: every pixel of an image of the sky
 * must equal the mean of the map's lookups over the pixel's footprint (a
 * box filter; 8 x 8 directions through the same camera model). */
#include "pt_scenes.h"
#include "image/envmap.h"

static il_image read_map(const char *file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/envmaps/%s", IL_SHARED_DIR, file);
    il_image img = {0};
    CHECK_OK(il_image_read(path, &img, &g_err), &g_err);
    return img;
}

/* Our own rotation about +y by `deg`, counter-clockwise seen from above:
 * the world direction of a map direction. */
static il_vec3 turn(il_vec3 d, double deg)
{
    double a = deg * PI_D / 180.0, c = cos(a), s = sin(a);
    return v3((float)(d.x * c + d.z * s), d.y, (float)(-d.x * s + d.z * c));
}

/* E = int L(w) max(0, w.n) dOmega of a lat-long map turned by rot, times k. */
static il_vec3 irradiance(const il_image *map, double rot, float k, il_vec3 n)
{
    const int q = 4;
    double e[3] = {0, 0, 0};
    for (uint32_t y = 0; y < map->height; y++)
        for (int b = 0; b < q; b++) {
            double v = (y + (b + 0.5) / q) / map->height;
            double dw = 2.0 * PI_D * PI_D * sin(PI_D * v) / ((double)map->width * map->height * q * q);
            for (uint32_t x = 0; x < map->width; x++)
                for (int a = 0; a < q; a++) {
                    float u = (float)((x + (a + 0.5) / q) / map->width);
                    il_vec3 local;
                    il_envmap_uv_to_dir(IL_ENV_LATLONG, v2(u, (float)v), &local);
                    double c = v3_dot(turn(local, rot), n);
                    if (c <= 0.0)
                        continue;
                    il_vec3 L = il_envmap_lookup(map, IL_ENV_LATLONG, local);
                    e[0] += L.x * c * dw;
                    e[1] += L.y * c * dw;
                    e[2] += L.z * c * dw;
                }
        }
    double kk = k > 0.0f ? k : 1.0;   /* intensity 0 means 1 */
    return v3((float)(kk * e[0]), (float)(kk * e[1]), (float)(kk * e[2]));
}

static il_scene *plane_scene(const il_image *map, float rot, float k, il_vec3 n, float rho)
{
    il_scene *s = new_scene();
    uint32_t mat = add_material(s, (il_material_desc){.diffuse = v3s(rho)});
    il_frame f = il_frame_from_normal(n);
    /* Front face = cross(ex, ey) = n. */
    add_quad(s, v3(0, 0, 0), v3_scale(f.s, 50.0f), v3_scale(f.t, 50.0f), mat);
    il_vec3 up = fabsf(n.y) > 0.9f ? v3(0, 0, -1) : v3(0, 1, 0);
    set_camera(s, n, v3(0, 0, 0), up, 30.0f);
    il_environment_desc env = {.map = map, .mapping = IL_ENV_LATLONG, .rotation = rot, .intensity = k};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    commit(s);
    return s;
}

/* Mean and standard error of the mean of channel c over the pixels. */
static void pixel_stats(const il_image *img, int c, double *mean, double *se)
{
    size_t n = (size_t)img->width * img->height;
    double s = 0.0, s2 = 0.0;
    for (size_t i = 0; i < n; i++) {
        double v = img->rgb[3 * i + c];
        s += v;
        s2 += v * v;
    }
    *mean = s / n;
    *se = sqrt(fmax(0.0, s2 / n - *mean * *mean) / (n - 1));
}

static void plane(const il_image *map, const char *name, float rot, float k, il_vec3 n, il_pt_strategy strategy,
                  uint32_t spp)
{
    const float rho = 0.6f;
    n = v3_normalize(n);
    il_scene *s = plane_scene(map, rot, k, n, rho);
    il_render_desc rd = {.spp = spp, .seed = 11, .max_depth = 4};
    il_render_stats st;
    il_image img = render_image(s, 32, 32, &rd, strategy, &st);
    CHECK(img.rgb && image_finite(&img) && st.nonfinite_samples == 0);
    il_vec3 e = irradiance(map, rot, k, n);
    const char *sname = strategy == IL_PT_MIS ? "NEE+MIS" : "NEE only";
    for (int c = 0; c < 3 && img.rgb; c++) {
        double expect = rho / PI_D * v3_get(e, c), mean, se;
        pixel_stats(&img, c, &mean, &se);
        printf("%s rot %g n (%.2f %.2f %.2f) %s %u spp ch %d: %.5f expected %.5f (%+.3f%%, %.1f standard errors)\n",
               name, rot, n.x, n.y, n.z, sname, spp, c, mean, expect, 100.0 * (mean / expect - 1.0),
               (mean - expect) / se);
        /* Within 4 standard errors, and the standard error itself small
         * (below 1%): the test can tell a wrong pdf (MIS weights) or a
         * wrong rotation from noise. */
        CHECK(fabs(mean - expect) <= 4.0 * se);
        CHECK(se < 0.01 * expect);
    }
    il_image_free(&img);
    il_scene_release(s);
}

/* Camera rays that miss everything show the map. */
static void background(const il_image *map, float rot, float k)
{
    il_scene *s = new_scene();
    /* A small triangle behind the camera: a scene needs geometry. */
    add_quad(s, v3(0, 0, 50), v3(0.1f, 0, 0), v3(0, 0.1f, 0), 0);
    set_camera(s, v3(0, 0, 0), v3(0.8f, 0.3f, -1.0f), v3(0, 1, 0), 10.0f);
    il_environment_desc env = {.map = map, .mapping = IL_ENV_LATLONG, .rotation = rot, .intensity = k};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    commit(s);
    const uint32_t w = 24, h = 16;
    il_render_desc rd = {.spp = 256, .seed = 2};
    il_image img = render_image(s, w, h, &rd, IL_PT_MIS, NULL);
    il_camera_desc cd;
    il_scene_get_camera(s, &cd);
    il_camera cam;
    il_camera_init(&cam, &cd, w, h);
    double worst = 0.0, sum_err = 0.0, sum_ref = 0.0;
    for (uint32_t y = 0; img.rgb && y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            double ref = 0.0;
            for (int b = 0; b < 8; b++)
                for (int a = 0; a < 8; a++) {
                    il_vec3 d = il_camera_ray_dir(&cam, x + (a + 0.5f) / 8, y + (b + 0.5f) / 8);
                    /* The map's direction: turned back by our own formula. */
                    ref += il_luminance(il_envmap_lookup(map, IL_ENV_LATLONG, turn(d, -rot))) * k / 64.0;
                }
            const float *p = img.rgb + 3 * ((size_t)y * w + x);
            double got = il_luminance(v3(p[0], p[1], p[2]));
            worst = fmax(worst, fabs(got - ref) / ref);
            sum_err += fabs(got - ref);
            sum_ref += ref;
        }
    printf("background rot %g: pixels against the map's lookups: mean error %.3f%%, worst %.3f%%\n", rot,
           100.0 * sum_err / sum_ref, 100.0 * worst);
    /* 256 samples per pixel against 64 fixed directions: what differs is
     * the estimate of the mean over a pixel (0.4 of a texel wide). */
    CHECK(sum_err / sum_ref < 0.005);
    CHECK(worst < 0.03);
    il_image_free(&img);
    il_scene_release(s);
}

int main(void)
{
    il_image grace = read_map("probulator_grace_256x128.hdr");
    il_image sun = read_map("polyhaven_pedestrian_overpass_1k.hdr");
    if (grace.rgb) {
        plane(&grace, "grace", 0.0f, 0.0f, v3(0, 1, 0), IL_PT_MIS, 64);
        plane(&grace, "grace", 30.0f, 2.0f, v3(0.6f, 0.5f, -0.3f), IL_PT_MIS, 64);
        plane(&grace, "grace", 30.0f, 2.0f, v3(0.6f, 0.5f, -0.3f), IL_PT_NEE_ONLY, 64);
        background(&grace, 30.0f, 1.0f);
    }
    if (sun.rgb) {
        plane(&sun, "overpass", 0.0f, 0.0f, v3(0, 1, 0), IL_PT_MIS, 64);
        plane(&sun, "overpass", -75.0f, 0.0f, v3(-0.3f, 0.4f, 0.8f), IL_PT_MIS, 64);
        plane(&sun, "overpass", -75.0f, 0.0f, v3(-0.3f, 0.4f, 0.8f), IL_PT_NEE_ONLY, 64);
        background(&sun, -75.0f, 1.0f);
    }
    il_image_free(&grace);
    il_image_free(&sun);
    return check_report();
}
