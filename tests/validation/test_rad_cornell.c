/* Radiosity against the path tracer on the built-in (diffuse) Cornell box:
 * the mean radiance over the pixels of each wall and block agrees within 3%.
 * Pixels are assigned to a scene mesh by the camera ray through their centre
 * (the same mask for both images); the path tracer runs deep (radiosity has
 * every bounce). */
#include "rad_scenes.h"

#define W 64
#define H 64

static void compare(const il_scene *s, const il_image ref, il_form_factor_method ff)
{
    il_radiosity_desc rad = {.form_factors = ff, .ray_samples = 2048, .tolerance = 1e-3f};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .spp = 16, .threads = 2, .seed = 3,
                         .radiosity = &rad};
    il_film *film = NULL;
    CHECK_OK(il_film_create(W, H, &film, &g_err), &g_err);
    il_render_stats st;
    CHECK_OK(il_render(s, film, &rd, &st, &g_err), &g_err);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    il_film_release(film);
    printf("radiosity (%s): %u patches, %u shots, unshot %.4f\n",
           ff == IL_FF_HEMICUBE ? "hemicube" : "ray-cast", st.radiosity.num_patches,
           st.radiosity.steps, st.radiosity.unshot_fraction);

    /* Which scene mesh each pixel centre sees. */
    il_camera cam;
    il_camera_init(&cam, &s->camera.desc, W, H);
    double sum_a[16][3] = {{0}}, sum_b[16][3] = {{0}};
    uint32_t count[16] = {0};
    for (uint32_t y = 0; ref.rgb && img.rgb && y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            il_ray ray = {.org = cam.position, .tmin = 0.0f,
                          .dir = il_camera_ray_dir(&cam, x + 0.5f, y + 0.5f), .tmax = INFINITY};
            il_hit hit;
            if (!il_trace_closest(s->tracer, &ray, &hit) || hit.mesh >= 16)
                continue;
            count[hit.mesh]++;
            for (int c = 0; c < 3; c++) {
                sum_a[hit.mesh][c] += img.rgb[3 * (y * W + x) + c];
                sum_b[hit.mesh][c] += ref.rgb[3 * (y * W + x) + c];
            }
        }
    uint32_t compared = 0;
    for (uint32_t m = 0; m < s->num_meshes && m < 16; m++) {
        if (count[m] < 40 || !v3_is_zero(s->materials[s->meshes[m].material].emission))
            continue; /* too few pixels for a stable mean, or the lamp */
        compared++;
        double la = 0.2126 * sum_a[m][0] + 0.7152 * sum_a[m][1] + 0.0722 * sum_a[m][2];
        double lb = 0.2126 * sum_b[m][0] + 0.7152 * sum_b[m][1] + 0.0722 * sum_b[m][2];
        printf("%-18s %5u px  radiosity %.4f  pt %.4f  (%+.2f%%)\n", s->meshes[m].name, count[m],
               la / count[m], lb / count[m], 100.0 * (la - lb) / lb);
        CHECK_REL(la, lb, 0.03);
        for (int c = 0; c < 3; c++)
            CHECK_REL(sum_a[m][c], sum_b[m][c], 0.05);
    }
    CHECK(compared >= 6);
    il_image_free(&img);
}

int main(void)
{
    il_scene *s = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &s, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    if (!s || !s->committed)
        return check_report();

    il_render_desc pt = {.method = IL_METHOD_PT, .spp = 512, .max_depth = 64, .threads = 2, .seed = 3};
    il_image ref = render_image(s, W, H, &pt, IL_PT_MIS, NULL);
    compare(s, ref, IL_FF_HEMICUBE);
    compare(s, ref, IL_FF_RAYCAST);
    il_image_free(&ref);
    il_scene_release(s);
    return check_report();
}
