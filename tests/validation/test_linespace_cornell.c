/* Linespace light injection against the path tracer on the built-in
 * (diffuse) Cornell box, both at max depth 8:
 * - the mean radiance over the pixels of each wall and block within 8%
 *   (the issue asks 10% for the walls), with the default variant
 *   (occlusion test on, occluded entries trace on, empty ones read as no
 *   light) and 1M injected paths; with empty entries tracing on too
 *   (`--fallback on`) more lookups trace and the walls stay within 10%;
 * - the pure Linespace read (no occlusion test, no fallback: every camera
 *   path ends at its first diffuse hit) gets closer to the path tracer as
 *   the injected paths grow (RMS difference, 40k -> 1.2M paths; its
 *   per-mesh means are printed only: see below);
 * - the solid-angle weighting (each shaft normalised by its own measure)
 *   gives a smaller error than the thesis's uniform normalisation;
 * - the coarse level (--coarse on): more lookups find light, and every
 *   wall and block stays within 10%;
 * - the final gather (one traced bounce before the read): every wall and
 *   block within 5%, the sum of the per-mesh errors under 3/4 of the
 *   default variant's;
 * - the same seed gives the same image with 1 and 2 threads;
 * - the stats: grid, shafts at most 15 N^4 per voxel, memory, lookups. */
#include <string.h>

#include "mesh_compare.h"

#define W 64
#define H 64

static il_image render_ls(const il_scene *s, const il_linespace_desc *ld, int threads, il_render_stats *st)
{
    il_render_desc rd = {.method = IL_METHOD_LINESPACE, .spp = 16, .max_depth = 8, .threads = threads,
                         .seed = 5, .linespace = ld};
    return render_desc_image(s, W, H, &rd, st);
}

/* Sum over the meshes of |mean a - mean b| / mean b (luminance). */
static double mesh_error(const il_scene *s, const il_image *a, const il_image *b)
{
    uint32_t *mask = mesh_mask(s, W, H);
    double total = 0.0;
    for (uint32_t m = 0; mask && m < s->num_meshes; m++) {
        double la = 0.0, lb = 0.0;
        uint32_t count = 0;
        for (size_t i = 0; i < (size_t)W * H; i++)
            if (mask[i] == m) {
                const float *pa = a->rgb + 3 * i, *pb = b->rgb + 3 * i;
                la += 0.2126 * pa[0] + 0.7152 * pa[1] + 0.0722 * pa[2];
                lb += 0.2126 * pb[0] + 0.7152 * pb[1] + 0.0722 * pb[2];
                count++;
            }
        if (count >= 40 && lb > 0.0)
            total += fabs(la - lb) / lb;
    }
    free(mask);
    return total;
}

/* The walls' mean radiance (the meshes not named "...block") within tol
 * of the reference's; returns how many were compared. */
static int walls_within(const il_scene *s, const il_image *a, const il_image *b, double tol)
{
    uint32_t *mask = mesh_mask(s, W, H);
    int compared = 0;
    for (uint32_t m = 0; mask && m < s->num_meshes; m++) {
        if (strstr(s->meshes[m].name, "block") ||
            !v3_is_zero(s->materials[s->meshes[m].material].emission))
            continue;
        double la = 0.0, lb = 0.0;
        for (size_t i = 0; i < (size_t)W * H; i++)
            if (mask[i] == m) {
                const float *pa = a->rgb + 3 * i, *pb = b->rgb + 3 * i;
                la += 0.2126 * pa[0] + 0.7152 * pa[1] + 0.0722 * pa[2];
                lb += 0.2126 * pb[0] + 0.7152 * pb[1] + 0.0722 * pb[2];
            }
        if (lb <= 0.0)
            continue;
        compared++;
        CHECK_REL(la, lb, tol);
    }
    free(mask);
    return compared;
}

int main(void)
{
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    il_render_desc pt = {.method = IL_METHOD_PT, .spp = 512, .max_depth = 8, .threads = 2, .seed = 3};
    il_image ref = render_desc_image(s, W, H, &pt, NULL);

    /* The default variant. */
    il_linespace_desc def = {.inject_rays = 1000000};
    il_render_stats st;
    il_image img = render_ls(s, &def, 2, &st);
    const il_linespace_stats *ls = &st.linespace;
    printf("linespace: grid %ux%ux%u, %llu voxels, %llu shafts, %.1f MB, %llu segments, "
           "lookups %llu (found %llu, empty %llu, occluded %llu)\n",
           ls->grid[0], ls->grid[1], ls->grid[2], (unsigned long long)ls->voxels,
           (unsigned long long)ls->shafts, ls->memory_bytes / 1048576.0,
           (unsigned long long)ls->injected_segments, (unsigned long long)ls->lookups,
           (unsigned long long)ls->lookup_hits, (unsigned long long)ls->lookup_empty,
           (unsigned long long)ls->lookup_occluded);
    CHECK(ls->grid[0] == 8 && ls->grid[1] == 8 && ls->grid[2] == 8 && ls->n == 4);
    CHECK(ls->voxels > 200 && ls->voxels < 512);
    CHECK(ls->shafts > 0 && ls->shafts <= ls->voxels * 3840u);
    CHECK(ls->memory_bytes > ls->shafts * 32u);
    CHECK(ls->inject_rays == 1000000 && ls->injected_segments > 1000000);
    CHECK(ls->lookups > 0 && ls->lookup_hits > ls->lookups / 2);
    CHECK(ls->lookup_hits + ls->lookup_empty + ls->lookup_occluded == ls->lookups);
    CHECK(image_finite(&img));
    CHECK(compare_mesh_means(s, &img, &ref, 0.08, 0.0, "linespace", "pt") >= 6);
    printf("default: rel. RMS difference %.4f\n", rel_rms(&img, &ref));

    /* Empty entries trace on too: the same lookups, as many traced. */
    il_linespace_desc on = {.inject_rays = 1000000, .fallback_empty = true};
    il_render_stats ost;
    il_image oimg = render_ls(s, &on, 2, &ost);
    printf("fallback on: lookups %llu (found %llu, empty %llu, occluded %llu), rel. RMS difference %.4f\n",
           (unsigned long long)ost.linespace.lookups, (unsigned long long)ost.linespace.lookup_hits,
           (unsigned long long)ost.linespace.lookup_empty, (unsigned long long)ost.linespace.lookup_occluded,
           rel_rms(&oimg, &ref));
    CHECK(image_finite(&oimg));
    CHECK(ost.linespace.lookup_empty > 0 && ost.linespace.lookups > ls->lookups);
    /* The walls within 10%; the blocks printed: a traced estimate in place
     * of an empty entry's zero biases upwards (docs/linespace.md). */
    CHECK(walls_within(s, &oimg, &ref, 0.10) == 5);
    compare_mesh_means(s, &oimg, &ref, 1.0, 0.0, "fallback-on", "pt");
    il_image_free(&oimg);

    /* The coarse level. */
    il_linespace_desc co = {.inject_rays = 1000000, .coarse = true};
    il_render_stats cst;
    il_image cimg = render_ls(s, &co, 2, &cst);
    const il_linespace_stats *cl = &cst.linespace;
    double found = (double)ls->lookup_hits / (double)ls->lookups;
    double cfound = (double)cl->lookup_hits / (double)cl->lookups;
    printf("coarse: lookups %llu, found %.1f%% (%.1f%% from the coarse level; fine only %.1f%%), "
           "%.1f MB, rel. RMS difference %.4f\n",
           (unsigned long long)cl->lookups, 100.0 * cfound, 100.0 * (double)cl->lookup_coarse / (double)cl->lookups,
           100.0 * found, cl->memory_bytes / 1048576.0, rel_rms(&cimg, &ref));
    CHECK(cl->lookup_coarse > 0 && cl->lookup_coarse <= cl->lookup_hits);
    CHECK(cl->lookup_hits + cl->lookup_empty + cl->lookup_occluded == cl->lookups);
    CHECK(cfound > found + 0.15);
    CHECK(cl->memory_bytes > ls->memory_bytes);
    CHECK(image_finite(&cimg));
    CHECK(walls_within(s, &cimg, &ref, 0.10) == 5);
    CHECK(compare_mesh_means(s, &cimg, &ref, 0.10, 0.0, "coarse", "pt") >= 6);
    il_image_free(&cimg);

    /* The final gather. */
    il_linespace_desc fg = {.inject_rays = 1000000, .trace_first_bounce = true};
    il_render_stats fst;
    il_image fimg = render_ls(s, &fg, 2, &fst);
    printf("final gather: lookups %llu (default %llu), rel. RMS difference %.4f\n",
           (unsigned long long)fst.linespace.lookups, (unsigned long long)ls->lookups, rel_rms(&fimg, &ref));
    CHECK(image_finite(&fimg));
    CHECK(compare_mesh_means(s, &fimg, &ref, 0.05, 0.0, "gather", "pt") >= 6);
    double m_def = mesh_error(s, &img, &ref), m_fg = mesh_error(s, &fimg, &ref);
    printf("sum of per-mesh errors: default %.4f, final gather %.4f\n", m_def, m_fg);
    CHECK(m_fg < 0.75 * m_def);
    il_image_free(&fimg);

    /* Determinism across thread counts. */
    il_linespace_desc small = {.inject_rays = 100000};
    il_image a = render_ls(s, &small, 1, NULL), b = render_ls(s, &small, 2, NULL);
    CHECK(a.rgb && b.rgb && !memcmp(a.rgb, b.rgb, sizeof(float) * 3 * W * H));
    il_image_free(&a);
    il_image_free(&b);

    /* The pure read: error shrinks with the injected paths. */
    il_linespace_desc pure = {.no_occlusion_test = true, .no_fallback = true, .inject_rays = 40000};
    il_image few = render_ls(s, &pure, 2, NULL);
    pure.inject_rays = 1200000;
    il_image many = render_ls(s, &pure, 2, NULL);
    double e_few = rel_rms(&few, &ref), e_many = rel_rms(&many, &ref);
    printf("pure read: rel. RMS 40k paths %.4f, 1.2M paths %.4f\n", e_few, e_many);
    CHECK(e_many < 0.7 * e_few);
    /* Printed, not checked per mesh: without the occlusion test a point
     * reads the light entering its voxel even where a nearer surface lies
     * between (the tall block about 11% low). */
    compare_mesh_means(s, &many, &ref, 1.0, 0.0, "ls-pure", "pt");

    /* The solid-angle weighting against the uniform normalisation. */
    pure.no_solid_angle = true;
    il_image uni = render_ls(s, &pure, 2, NULL);
    double m_sa = mesh_error(s, &many, &ref), m_uni = mesh_error(s, &uni, &ref);
    double r_uni = rel_rms(&uni, &ref);
    printf("solid angle on: sum of per-mesh errors %.4f, rel. RMS %.4f; off: %.4f, %.4f\n", m_sa, e_many,
           m_uni, r_uni);
    CHECK(m_sa < 0.5 * m_uni);
    CHECK(e_many < r_uni);

    il_image_free(&few);
    il_image_free(&many);
    il_image_free(&uni);
    il_image_free(&img);
    il_image_free(&ref);
    il_scene_release(s);
    return check_report();
}
