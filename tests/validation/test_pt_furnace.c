/* Furnace test: inside a closed box whose walls all emit E and reflect with
 * diffuse albedo rho, the radiance is the same everywhere and in every
 * direction, L = E + rho L, so L = E / (1 - rho) (the rendering equation
 * with constant L; e.g. Pharr et al., pbrt-v4 section 13.1).  The path
 * tracer must find it within 1%, per channel, over the whole image. */
#include "pt_scenes.h"

static il_scene *furnace_box(il_vec3 e, float rho)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = v3s(rho), .emission = e});
    add_cube(s, m, true);
    set_camera(s, v3(0.1f, 0.2f, 0.3f), v3(1, -0.5f, -1), v3(0, 1, 0), 70.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

static void check_furnace(float rho, il_sampler_type sampler, il_filter_type filter,
                          il_pt_strategy strategy, uint32_t spp, double tol)
{
    const il_vec3 e = v3(1.0f, 0.5f, 0.25f);
    il_scene *s = furnace_box(e, rho);
    il_render_desc rd = {.spp = spp, .max_depth = 64, .seed = 3, .sampler = sampler, .filter = filter};
    il_render_stats st;
    il_image img = render_image(s, 32, 32, &rd, strategy, &st);
    CHECK(img.rgb && image_finite(&img));
    CHECK(st.spp == spp && st.nonfinite_samples == 0);
    for (int c = 0; c < 3; c++) {
        double expect = v3_get(e, c) / (1.0 - rho);
        double mean = image_mean(&img, c);
        printf("furnace rho %.2f sampler %d filter %d strategy %d channel %d: %.5f expected %.5f (%+.3f%%)\n",
               rho, sampler, filter, strategy, c, mean, expect, 100.0 * (mean / expect - 1.0));
        CHECK_REL(mean, expect, tol);
        /* Each quarter of the image too (looser: a quarter of the samples). */
        CHECK_REL(region_mean(&img, 0, 0, 16, 16, c), expect, 2.0 * tol);
        CHECK_REL(region_mean(&img, 16, 16, 32, 32, c), expect, 2.0 * tol);
    }
    il_image_free(&img);
    il_scene_release(s);
}

int main(void)
{
    check_furnace(0.5f, IL_SAMPLER_SOBOL, IL_FILTER_BOX, IL_PT_MIS, 64, 0.01);
    check_furnace(0.8f, IL_SAMPLER_SOBOL, IL_FILTER_BOX, IL_PT_MIS, 128, 0.01);
    check_furnace(0.5f, IL_SAMPLER_PCG, IL_FILTER_GAUSSIAN, IL_PT_MIS, 64, 0.01);
    check_furnace(0.5f, IL_SAMPLER_SOBOL, IL_FILTER_BOX, IL_PT_BSDF_ONLY, 64, 0.01);
    /* Light sampling alone has a heavy tail here: near the box's edges the
     * adjacent wall is sampled at cos cos / d^2 without bound, so a few rare
     * samples carry much of the mean (MIS exists to cure exactly this).  It
     * converges, but more slowly: a looser bound. */
    check_furnace(0.5f, IL_SAMPLER_SOBOL, IL_FILTER_BOX, IL_PT_NEE_ONLY, 64, 0.03);
    return check_report();
}
