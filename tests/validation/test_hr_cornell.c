/* Hierarchical radiosity against the path tracer on the built-in (diffuse)
 * Cornell box: the mean radiance over the pixels of each wall and block
 * agrees within 3% (luminance; 6% per channel).  The path tracer runs deep
 * (radiosity has every bounce).  bf_eps 0.005 (within 2.3%; the default
 * 0.015 gives up to -3.8% on the floor and the tall block). */
#include "hr_scenes.h"

#define W 64
#define H 64

int main(void)
{
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();

    il_render_desc pt = {.method = IL_METHOD_PT, .spp = 512, .max_depth = 64, .threads = 2, .seed = 3};
    il_image ref = render_image(s, W, H, &pt, IL_PT_MIS, NULL);

    il_hr_desc hd = {.bf_eps = 0.005f, .energy_eps = 1e-4f};
    il_render_desc rd = {.method = IL_METHOD_HR, .spp = 16, .threads = 2, .seed = 3, .hr = &hd};
    il_render_stats st;
    il_image img = render_desc_image(s, W, H, &rd, &st);
    hr_print_stats("hr", &st.hr);
    CHECK(st.hr.patches > 10 && st.hr.elements > st.hr.patches && st.spp == 16);
    CHECK(compare_mesh_means(s, &img, &ref, 0.03, 0.06, "hr", "pt") >= 6);
    il_image_free(&img);
    il_image_free(&ref);
    il_scene_release(s);
    return check_report();
}
