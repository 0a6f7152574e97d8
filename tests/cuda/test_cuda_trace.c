/* GPU ray casting (src/cuda/trace_kernel.cu) against the same shared kernel
 * compiled by gcc (kernel/kernel_bvh.h): on the Cornell box and the Stanford
 * bunny, the GPU finds the same closest triangle, t and barycentrics and
 * the same occlusion answers: the same bits, as both builds round every
 * operation alike (illum_cuda is compiled with -fmad=false; on an H200, 0
 * differences in 2^21 rays; with nvcc's FMA contraction t or barycentrics
 * moved by up to 1.8e-3 and 5 bunny rays hit another triangle).  Exits 77
 * (a skip for ctest) when there is no GPU or no driver: the CI machines
 * have none. */
#include <stdlib.h>
#include <string.h>
#include "core/rng.h"
#include "cuda_test.h"
#include "scene/scene.h"

static int compare(const char *name, const char *path, uint32_t n)
{
    il_error err = {0};
    il_scene *s = NULL;
    il_kbvh b = {0};
    CHECK_OK(il_scene_load(path, NULL, &s, &err), &err);
    if (!s)
        return 0;
    CHECK_OK(il_kbvh_build_scene(s, &b, &err), &err);
    ilk_vec3 lo = ilk_v3(b.nodes[0].lo[0], b.nodes[0].lo[1], b.nodes[0].lo[2]);
    ilk_vec3 hi = ilk_v3(b.nodes[0].hi[0], b.nodes[0].hi[1], b.nodes[0].hi[2]);
    ilk_ray *rays = malloc(sizeof *rays * n);
    ilk_hit *gh = malloc(sizeof *gh * n);
    uint8_t *go = malloc(n);
    il_pcg32 rng = il_pcg32_seed(7, 11);
    for (uint32_t i = 0; i < n; i++) {
        /* From a random point of the box grown by half towards a random
         * point of the box: most rays hit; every other one is a segment. */
        float a[3], c[3];
        for (int k = 0; k < 3; k++) {
            float l = ilk_comp(lo, k), h = ilk_comp(hi, k), m = 0.5f * (l + h), r = 0.75f * (h - l);
            a[k] = m + (2 * il_pcg32_float(&rng) - 1) * r;
            c[k] = l + il_pcg32_float(&rng) * (h - l);
        }
        rays[i].org = ilk_v3(a[0], a[1], a[2]);
        rays[i].dir = ilk_sub(ilk_v3(c[0], c[1], c[2]), rays[i].org);
        rays[i].tmin = 0;
        rays[i].tmax = (i & 1) ? 1.0f : INFINITY;
    }
    il_status st = il_cuda_trace_rays(&b, rays, n, gh, go, &err);
    CHECK_OK(st, &err);
    int same = 0, differ = 0, occ_differ = 0, hits = 0;
    double max_rel = 0;
    ilk_bvh kb = il_kbvh_view(&b);
    for (uint32_t i = 0; st == IL_OK && i < n; i++) {
        ilk_hit ch;
        bool c = ilk_bvh_closest(&kb, &rays[i], &ch);
        bool o = ilk_bvh_occluded(&kb, &rays[i]);
        occ_differ += o != (go[i] != 0);
        if (c != (gh[i].tri != UINT32_MAX) || (c && ch.tri != gh[i].tri)) {
            differ++;
            continue;
        }
        if (!c)
            continue;
        hits++;
        same++;
        double rel = fabs((double)gh[i].t - ch.t) / ch.t;
        double db = fmax(fabs((double)gh[i].b1 - ch.b1), fabs((double)gh[i].b2 - ch.b2));
        if (rel > max_rel) max_rel = rel;
        if (db > max_rel) max_rel = db;
    }
    printf("%s: %u rays, %d hits on the same triangle (max rel dt / dbary %.3g), %d differ, %d occlusion differ\n",
           name, n, same, max_rel, differ, occ_differ);
    CHECK(hits > (int)n / 4);
    CHECK(max_rel <= 1e-5);
    CHECK(differ <= (int)n / 10000); /* a ray through an edge may go either way */
    CHECK(occ_differ <= (int)n / 10000);
    free(rays); free(gh); free(go);
    il_kbvh_free(&b);
    il_scene_release(s);
    return 0;
}

int main(void)
{
    if (cuda_test_require_gpu() != 0)
        return 77;
    compare("cornell", "cornell", 1u << 20);
    compare("bunny", IL_SHARED_DIR "/scenes/stanford-bunny/bun_zipper.ply", 1u << 20);
    return check_report();
}
