/* The path tracer's wavefront camera pass (pt_wavefront.c) against the
 * shared camera pass with il_pt_radiance traced one ray at a time: the same
 * estimator, the same sample numbers, the same film, bit for bit, for every
 * strategy, sampler, filter, thread count and a sample count that spans
 * several waves per tile. */
#include "pt_scenes.h"

#include "methods/camera_pass.h"

enum { W = 37, H = 21 }; /* partial tiles at the right and bottom */

typedef struct scalar_method {
    const il_scene *scene;
    uint32_t max_depth;
    il_pt_strategy strategy;
} scalar_method;

static il_vec3 scalar_radiance(const void *method, il_vec3 org, il_vec3 dir, il_sampler *smp,
                               uint64_t *rays)
{
    const scalar_method *m = method;
    return il_pt_radiance(m->scene, org, dir, smp, m->max_depth, m->strategy, rays);
}

/* Diffuse, Phong, mirror and glass under an area lamp, a point light and a sky. */
static il_scene *scene_all(void)
{
    il_scene *s = new_scene();
    uint32_t phong = add_material(s, (il_material_desc){.type = IL_MATERIAL_PHONG, .diffuse = v3(0.3f, 0.3f, 0.2f),
                                                         .specular = v3s(0.4f), .exponent = 30.0f});
    uint32_t red = add_material(s, (il_material_desc){.diffuse = v3(0.7f, 0.1f, 0.1f)});
    uint32_t mirror = add_material(s, (il_material_desc){.type = IL_MATERIAL_MIRROR, .specular = v3s(0.9f)});
    uint32_t glass = add_material(s, (il_material_desc){.type = IL_MATERIAL_DIELECTRIC, .ior = 1.5f});
    uint32_t lamp = add_material(s, (il_material_desc){.emission = v3(6, 6, 5)});
    add_floor(s, 0.0f, 2.0f, phong);
    add_quad(s, v3(-2, 1, 0), v3(0, 1, 0), v3(0, 0, 2), red);
    add_quad(s, v3(0, 1, -2), v3(1, 0, 0), v3(0, 1, 0), mirror);
    add_quad(s, v3(0.5f, 0.5f, 0), v3(0.3f, 0, 0), v3(0, 0.3f, 0), glass);
    add_quad(s, v3(0, 1.9f, 0), v3(0.3f, 0, 0), v3(0, 0, 0.3f), lamp);
    il_light_desc pl = {.type = IL_LIGHT_POINT, .position = {1, 1, 1}, .intensity = {0.5f, 0.5f, 0.5f}};
    CHECK_OK(il_scene_add_light(s, &pl, &g_err), &g_err);
    il_environment_desc env = {.radiance = v3(0.1f, 0.1f, 0.15f)};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
    set_camera(s, v3(0.3f, 1.2f, 3.5f), v3(0, 0.7f, 0), v3(0, 1, 0), 55.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

static il_image resolve(il_film *film)
{
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    return img;
}

int main(void)
{
    il_scene *s = scene_all();
    il_film *film = NULL;
    CHECK_OK(il_film_create(W, H, &film, &g_err), &g_err);
    const il_pt_strategy strategies[] = {IL_PT_MIS, IL_PT_NEE_ONLY, IL_PT_BSDF_ONLY};
    for (int k = 0; k < 3; k++)
        for (int type = IL_SAMPLER_SOBOL; type <= IL_SAMPLER_PCG; type++) {
            /* 37x21 pixels make 65536/777 = 84 samples per pass, capped at 64:
             * 70 spp is two passes, and a full tile's 16*16*64 samples fill
             * 64 waves. */
            il_render_desc rd = {.spp = 70, .seed = 5, .max_depth = 6, .threads = 1 + (k & 1),
                                 .sampler = (il_sampler_type)type,
                                 .filter = k == 1 ? IL_FILTER_GAUSSIAN : IL_FILTER_BOX};
            scalar_method m = {.scene = s, .max_depth = 6, .strategy = strategies[k]};
            il_camera_pass_result a, b;
            il_camera_pass(s, film, &rd, scalar_radiance, &m, &a);
            il_image ia = resolve(film);
            CHECK_OK(il_pt_wavefront_pass(s, film, &rd, 6, strategies[k], &b, &g_err), &g_err);
            il_image ib = resolve(film);
            CHECK(a.spp == 70 && b.spp == 70);
            CHECK(a.rays == b.rays && a.rays > (uint64_t)W * H * 70);
            CHECK(a.nonfinite_samples == b.nonfinite_samples);
            CHECK(ia.rgb && ib.rgb && memcmp(ia.rgb, ib.rgb, sizeof(float) * 3 * W * H) == 0);
            /* Not a black image: the comparison means something. */
            CHECK(image_mean(&ib, 1) > 0.01);
            il_image_free(&ia);
            il_image_free(&ib);
        }
    il_film_release(film);
    il_scene_release(s);
    return check_report();
}
