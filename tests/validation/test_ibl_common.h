/* Helpers for the ibl method's tests: environments (constant or a map from
 * ../shared/scenes/envmaps), rendering with an il_ibl_desc, comparing
 * images by regions.  Scenes: tests/scene_build.h; means: pt_scenes.h. */
#ifndef IL_TESTS_IBL_COMMON_H
#define IL_TESTS_IBL_COMMON_H

#include "pt_scenes.h"
#include "methods/ibl/ibl.h"

static inline void set_sky(il_scene *s, il_vec3 L)
{
    il_environment_desc env = {.radiance = L};
    CHECK_OK(il_scene_set_environment(s, &env, &g_err), &g_err);
}

/* A lat-long map of ../shared/scenes/envmaps; false (a failed check) when
 * it cannot be read. */
static inline bool set_map(il_scene *s, const char *file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/envmaps/%s", IL_SHARED_DIR, file);
    il_image map = {0};
    il_status st = il_image_read(path, &map, &g_err);
    CHECK_OK(st, &g_err);
    if (st != IL_OK)
        return false;
    il_environment_desc env = {.map = &map, .mapping = IL_ENV_LATLONG};
    st = il_scene_set_environment(s, &env, &g_err);
    CHECK_OK(st, &g_err);
    il_image_free(&map);
    return st == IL_OK;
}

static inline il_image render_ibl(const il_scene *s, uint32_t w, uint32_t h, const il_ibl_desc *d,
                                  uint32_t spp, uint64_t seed, il_render_stats *stats)
{
    il_render_desc rd = {.method = IL_METHOD_IBL, .spp = spp, .seed = seed, .ibl = d};
    return render_desc_image(s, w, h, &rd, stats);
}

static inline il_image render_pt_direct(const il_scene *s, uint32_t w, uint32_t h, uint32_t spp,
                                        uint64_t seed)
{
    il_render_desc rd = {.method = IL_METHOD_PT, .spp = spp, .seed = seed, .max_depth = 1};
    return render_desc_image(s, w, h, &rd, NULL);
}

static inline double luminance_mean(const il_image *img, uint32_t x0, uint32_t y0, uint32_t x1,
                                    uint32_t y1)
{
    return 0.2126 * region_mean(img, x0, y0, x1, y1, 0) + 0.7152 * region_mean(img, x0, y0, x1, y1, 1) +
           0.0722 * region_mean(img, x0, y0, x1, y1, 2);
}

/* Compares a with reference b: the whole image's mean luminance within
 * rel_mean, and every block x block region's within rel_region of the
 * reference (plus abs_floor, for dark regions).  Returns the worst
 * relative region error. */
static inline double compare_regions(const char *what, const il_image *a, const il_image *b,
                                     uint32_t block, double rel_mean, double rel_region,
                                     double abs_floor)
{
    double ma = luminance_mean(a, 0, 0, a->width, a->height);
    double mb = luminance_mean(b, 0, 0, b->width, b->height);
    printf("%s: mean luminance %.5f, reference %.5f (%+.2f%%)\n", what, ma, mb, 100.0 * (ma / mb - 1.0));
    CHECK_REL(ma, mb, rel_mean);
    double worst = 0.0;
    int bad = 0;
    for (uint32_t y = 0; y + block <= a->height; y += block)
        for (uint32_t x = 0; x + block <= a->width; x += block) {
            double ra = luminance_mean(a, x, y, x + block, y + block);
            double rb = luminance_mean(b, x, y, x + block, y + block);
            double e = fabs(ra - rb) / (rb + abs_floor);
            if (e > worst)
                worst = e;
            if (fabs(ra - rb) > rel_region * rb + abs_floor) {
                if (bad++ < 5)
                    fprintf(stderr, "%s: region (%u,%u) %.5f, reference %.5f\n", what, x, y, ra, rb);
            }
        }
    printf("%s: worst %ux%u region %.2f%%\n", what, block, block, 100.0 * worst);
    CHECK(bad == 0);
    return worst;
}

#endif
