/* Radiosity against the path tracer on the built-in (diffuse) Cornell box:
 * the mean radiance over the pixels of each wall and block agrees within 3%.
 * Pixels are assigned to a scene mesh by the camera ray through their centre
 * (the same mask for both images); the path tracer runs deep (radiosity has
 * every bounce). */
#include "mesh_compare.h"
#include "rad_scenes.h"

#define W 64
#define H 64

static void compare(const il_scene *s, const il_image ref, il_form_factor_method ff)
{
    il_radiosity_desc rad = {.form_factors = ff, .ray_samples = 2048, .tolerance = 1e-3f};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .spp = 16, .threads = 2, .seed = 3,
                         .radiosity = &rad};
    il_render_stats st;
    il_image img = render_desc_image(s, W, H, &rd, &st);
    printf("radiosity (%s): %u patches, %u shots, unshot %.4f\n",
           ff == IL_FF_HEMICUBE ? "hemicube" : "ray-cast", st.radiosity.num_patches,
           st.radiosity.steps, st.radiosity.unshot_fraction);

    CHECK(compare_mesh_means(s, &img, &ref, 0.03, 0.05, "radiosity", "pt") >= 6);
    il_image_free(&img);
}

int main(void)
{
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();

    il_render_desc pt = {.method = IL_METHOD_PT, .spp = 512, .max_depth = 64, .threads = 2, .seed = 3};
    il_image ref = render_image(s, W, H, &pt, IL_PT_MIS, NULL);
    compare(s, ref, IL_FF_HEMICUBE);
    compare(s, ref, IL_FF_RAYCAST);
    il_image_free(&ref);
    il_scene_release(s);
    return check_report();
}
