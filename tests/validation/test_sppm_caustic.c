/* A glass ball under a square lamp focuses its light onto the floor: the
 * caustic a path tracer can only find by BSDF sampling through the glass.
 * SPPM's radiance summed over the floor pixels around the caustic (those
 * the camera sees directly, not through the ball) is within 5% of a long
 * path-traced reference (the criterion), and the caustic is there:
 * the region is several times brighter than the lamp's direct light. */
#include "mesh_compare.h"

#define W 64
#define H 64
#define REGION 0.3f   /* metres around the point under the ball */

static il_scene *caustic_scene(void)
{
    il_scene *s = new_scene();
    uint32_t white = add_material(s, (il_material_desc){.type = IL_MATERIAL_DIFFUSE,
                                                        .diffuse = {0.8f, 0.8f, 0.8f}});
    uint32_t lamp = add_material(s, (il_material_desc){.type = IL_MATERIAL_DIFFUSE,
                                                       .emission = {20.0f, 20.0f, 20.0f}});
    uint32_t glass = add_material(s, (il_material_desc){.type = IL_MATERIAL_DIELECTRIC, .ior = 1.5f});
    add_floor(s, 0.0f, 1.5f, white);
    /* The lamp faces down: front face cross(ex, ey) = -y. */
    add_quad(s, v3(0.0f, 2.0f, 0.0f), v3(0.2f, 0.0f, 0.0f), v3(0.0f, 0.0f, 0.2f), lamp);
    add_ball(s, v3(0.0f, 0.5f, 0.0f), 0.25f, glass);
    set_camera(s, v3(0.0f, 1.6f, 1.8f), v3(0.0f, 0.0f, 0.0f), v3(0.0f, 1.0f, 0.0f), 40.0f);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

/* Luminance summed over the pixels whose centre sees the floor (mesh 0)
 * within REGION of the origin. */
static double region_sum(const il_scene *s, const il_image *img, const uint32_t *mask, uint32_t *n)
{
    double sum = 0.0;
    *n = 0;
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            il_vec3 p;
            if (mask[y * W + x] != 0 || !pixel_on_plane(s, W, H, x, y, 0.0f, &p) ||
                p.x * p.x + p.z * p.z > REGION * REGION)
                continue;
            const float *c = img->rgb + 3 * (y * W + x);
            sum += 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            (*n)++;
        }
    return sum;
}

int main(void)
{
    il_scene *s = caustic_scene();
    if (!s || !s->committed)
        return check_report();
    uint32_t *mask = mesh_mask(s, W, H);

    il_render_desc pt = {.method = IL_METHOD_PT, .spp = 4096, .max_depth = 16, .threads = 2, .seed = 1};
    il_image ref = render_desc_image(s, W, H, &pt, NULL);
    il_photon_desc pd = {.photons = 100000};
    il_render_desc rd = {.method = IL_METHOD_SPPM, .spp = 64, .max_depth = 16, .threads = 2,
                         .seed = 1, .photon = &pd};
    il_image img = render_desc_image(s, W, H, &rd, NULL);
    il_render_desc direct = {.method = IL_METHOD_PT, .spp = 64, .max_depth = 1, .threads = 2, .seed = 1};
    il_image dimg = render_desc_image(s, W, H, &direct, NULL);

    uint32_t n = 0;
    double e_pt = region_sum(s, &ref, mask, &n);
    double e_sppm = region_sum(s, &img, mask, &n);
    double e_direct = region_sum(s, &dimg, mask, &n);
    printf("caustic region, %u pixels: sppm %.4f, path tracer %.4f (%+.2f%%), direct light only %.4f\n",
           n, e_sppm / n, e_pt / n, 100.0 * (e_sppm - e_pt) / e_pt, e_direct / n);
    CHECK(n > 100);
    CHECK(e_pt > 3.0 * e_direct);
    CHECK_REL(e_sppm, e_pt, 0.05);

    il_image_free(&img);
    il_image_free(&dimg);
    il_image_free(&ref);
    free(mask);
    il_scene_release(s);
    return check_report();
}
