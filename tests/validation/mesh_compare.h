/* Comparing two renders of one scene: the mean radiance over the pixels of
 * each mesh (walls, blocks), and the RMS difference of the whole image. */
#ifndef IL_TESTS_MESH_COMPARE_H
#define IL_TESTS_MESH_COMPARE_H

#include <stdlib.h>

#include "pt_scenes.h"
#include "trace/trace.h"

/* The mesh the camera ray through the centre of each pixel hits first
 * (UINT32_MAX: none), into a new w*h array. */
static inline uint32_t *mesh_mask(const il_scene *s, uint32_t w, uint32_t h)
{
    uint32_t *mask = malloc((size_t)w * h * sizeof *mask);
    il_camera cam;
    il_camera_init(&cam, &s->camera.desc, w, h);
    for (uint32_t y = 0; mask && y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            il_ray ray = {.org = cam.position, .tmin = 0.0f,
                          .dir = il_camera_ray_dir(&cam, x + 0.5f, y + 0.5f), .tmax = INFINITY};
            il_hit hit;
            mask[y * w + x] = il_trace_closest(s->tracer, &ray, &hit) ? hit.mesh : UINT32_MAX;
        }
    return mask;
}

/* Per mesh, the mean radiance over its pixels in a and in reference b:
 * the luminance within tol (relative) and, when channel_tol > 0, each
 * channel within channel_tol, for every non-emitting mesh of at least 40
 * pixels (fewer make no stable mean).  Returns how many meshes were
 * compared. */
static inline uint32_t compare_mesh_means(const il_scene *s, const il_image *a, const il_image *b,
                                          double tol, double channel_tol, const char *label_a,
                                          const char *label_b)
{
    const uint32_t w = a->width, h = a->height;
    uint32_t *mask = mesh_mask(s, w, h);
    uint32_t compared = 0;
    for (uint32_t m = 0; mask && a->rgb && b->rgb && m < s->num_meshes; m++) {
        if (!v3_is_zero(s->materials[s->meshes[m].material].emission))
            continue;
        double sa[3] = {0, 0, 0}, sb[3] = {0, 0, 0};
        uint32_t count = 0;
        for (size_t i = 0; i < (size_t)w * h; i++)
            if (mask[i] == m) {
                for (int c = 0; c < 3; c++) {
                    sa[c] += a->rgb[3 * i + c];
                    sb[c] += b->rgb[3 * i + c];
                }
                count++;
            }
        if (count < 40)
            continue;
        compared++;
        double la = 0.2126 * sa[0] + 0.7152 * sa[1] + 0.0722 * sa[2];
        double lb = 0.2126 * sb[0] + 0.7152 * sb[1] + 0.0722 * sb[2];
        printf("%-18s %5u px  %s %.4f  %s %.4f  (%+.2f%%)\n",
               s->meshes[m].name[0] ? s->meshes[m].name : "mesh", count, label_a, la / count,
               label_b, lb / count, 100.0 * (la - lb) / lb);
        CHECK_REL(la, lb, tol);
        for (int c = 0; channel_tol > 0.0 && c < 3; c++)
            CHECK_REL(sa[c], sb[c], channel_tol);
    }
    free(mask);
    return compared;
}

/* Root-mean-square difference of the luminance of two images, relative to
 * the mean luminance of b. */
static inline double rel_rms(const il_image *a, const il_image *b)
{
    double se = 0.0, mean = 0.0;
    size_t n = (size_t)a->width * a->height;
    for (size_t i = 0; i < n; i++) {
        const float *pa = a->rgb + 3 * i, *pb = b->rgb + 3 * i;
        double la = 0.2126 * pa[0] + 0.7152 * pa[1] + 0.0722 * pa[2];
        double lb = 0.2126 * pb[0] + 0.7152 * pb[1] + 0.0722 * pb[2];
        se += (la - lb) * (la - lb);
        mean += lb;
    }
    mean /= (double)n;
    return mean > 0.0 ? sqrt(se / (double)n) / mean : 0.0;
}

#endif
