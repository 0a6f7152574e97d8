/* Hierarchical radiosity with tight epsilons against progressive radiosity
 * on a fine uniform mesh (through the public API), on a small closed room
 * with a shadowing block: the mean radiance over the pixels of each surface
 * agrees within 2%. */
#include "hr_scenes.h"

#define W 64
#define H 64

int main(void)
{
    il_scene *s = hr_room(false, true);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);

    il_radiosity_desc rad = {.subdivisions = 4, .tolerance = 1e-4f};
    il_render_desc rr = {.method = IL_METHOD_RADIOSITY, .spp = 16, .threads = 2, .seed = 5,
                         .radiosity = &rad};
    il_render_stats st;
    il_image ref = render_desc_image(s, W, H, &rr, &st);
    printf("radiosity: %u patches, %u steps\n", st.radiosity.num_patches, st.radiosity.steps);

    il_hr_desc hd = {.bf_eps = 0.005f, .energy_eps = 1e-4f};
    il_render_desc rd = {.method = IL_METHOD_HR, .spp = 16, .threads = 2, .seed = 5, .hr = &hd};
    il_image img = render_desc_image(s, W, H, &rd, &st);
    hr_print_stats("hr", &st.hr);
    CHECK(compare_mesh_means(s, &img, &ref, 0.02, 0.04, "hr", "radiosity") >= 6);
    il_image_free(&img);
    il_image_free(&ref);
    il_scene_release(s);
    return check_report();
}
