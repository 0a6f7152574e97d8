/* Photon mapping and SPPM give the same film with 1 and 2 threads (photon
 * i's path depends only on i and the seed; the maps and every pixel's sums
 * are formed in the same order), and a different seed gives another one. */
#include "mesh_compare.h"

#define W 32
#define H 32

static void check_method(const il_scene *s, il_method method, il_photon_desc pd)
{
    il_render_desc rd = {.method = method, .spp = 3, .threads = 1, .seed = 5, .photon = &pd};
    il_image one = render_desc_image(s, W, H, &rd, NULL);
    rd.threads = 2;
    il_image two = render_desc_image(s, W, H, &rd, NULL);
    rd.seed = 6;
    il_image other = render_desc_image(s, W, H, &rd, NULL);
    CHECK(image_finite(&one) && image_mean(&one, 1) > 0.0);
    CHECK(images_identical(&one, &two));
    CHECK(!images_identical(&one, &other));
    il_image_free(&one);
    il_image_free(&two);
    il_image_free(&other);
}

int main(void)
{
    il_scene *s = load_committed("cornell-spheres");
    if (!s)
        return check_report();
    check_method(s, IL_METHOD_PHOTON, (il_photon_desc){.photons = 50000});
    check_method(s, IL_METHOD_PHOTON, (il_photon_desc){.photons = 50000, .final_gather = 4,
                                                       .lookup = IL_PHOTON_GRID});
    check_method(s, IL_METHOD_SPPM, (il_photon_desc){.photons = 20000});
    check_method(s, IL_METHOD_SPPM, (il_photon_desc){.photons = 20000, .lookup = IL_PHOTON_GRID});
    il_scene_release(s);
    return check_report();
}
