/* Linespace injection from several kinds of light at once: the Cornell box
 * keeps its area light (emissive triangles, which the thesis could not
 * inject) and gets a point light and a spot light with a cos^4 profile.
 * Each path's flux carries 1 / (the light's selection probability), so the
 * lights mix by power, not by a shared counter (the thesis's Sponza error):
 * the mean radiance of every wall and block within 10% of the path
 * tracer (measured within 7.9%), with the spot as given and with it 4
 * times as bright (which changes every light's share of the paths). */
#include "mesh_compare.h"

#define W 48
#define H 48

static il_scene *scene(float spot_scale)
{
    il_scene *s = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &s, &g_err), &g_err);
    if (!s)
        return NULL;
    il_light_desc p = {.type = IL_LIGHT_POINT, .position = {0.15f, 0.42f, 0.35f},
                       .intensity = {0.04f, 0.035f, 0.03f}};
    il_light_desc sp = {.type = IL_LIGHT_SPOT, .position = {0.42f, 0.45f, 0.30f},
                        .direction = {-0.3f, -1.0f, 0.2f}, .intensity = {0.3f * spot_scale, 0.3f * spot_scale, 0.35f * spot_scale},
                        .spot_angle = 40.0f, .spot_exponent = 4.0f};
    CHECK_OK(il_scene_add_light(s, &p, &g_err), &g_err);
    CHECK_OK(il_scene_add_light(s, &sp, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

int main(void)
{
    const float scales[2] = {1.0f, 4.0f};
    for (int k = 0; k < 2; k++) {
        il_scene *s = scene(scales[k]);
        if (!s)
            return check_report();
        il_render_desc pt = {.method = IL_METHOD_PT, .spp = 384, .max_depth = 6, .threads = 2, .seed = 3};
        il_image ref = render_desc_image(s, W, H, &pt, NULL);
        il_linespace_desc ld = {.inject_rays = 1000000};
        il_render_desc rd = {.method = IL_METHOD_LINESPACE, .spp = 16, .max_depth = 6, .threads = 2,
                             .seed = 4, .linespace = &ld};
        il_render_stats st;
        il_image img = render_desc_image(s, W, H, &rd, &st);
        printf("spot x%g: %u lights, %llu segments injected\n", (double)scales[k], s->num_lights,
               (unsigned long long)st.linespace.injected_segments);
        CHECK(s->num_lights == 4);   /* two lamp triangles, the point, the spot */
        CHECK(compare_mesh_means(s, &img, &ref, 0.10, 0.0, "linespace", "pt") >= 6);
        il_image_free(&img);
        il_image_free(&ref);
        il_scene_release(s);
    }
    return check_report();
}
