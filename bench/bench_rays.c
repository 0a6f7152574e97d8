/* Rays per second: Embree alone vs the il_trace wrappers vs the path tracer.
 *
 *   bench_rays [SCENE] [--width W] [--height H] [--spp N]
 *
 * Records the rays of one path per pixel traced as the path tracer traces
 * them (camera, BSDF-sampled bounces, shadow rays to sampled lights), then
 * times the same batch cast (a) by Embree directly (rtcIntersect1/rtcOccluded1
 * on a scene built here), (b) through il_trace_closest/occluded, (c) through
 * the stream calls, each with 1 and 2 threads (best of three); last it
 * renders the scene with the path tracer (max depth 8) five times, each
 * right after an Embree-alone run, and reports its best rays/s and its
 * share of Embree's own rate: best over best, and the median of the five
 * pairs' ratios.  It prints figures and never judges them. */
#include <embree3/rtcore.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "scene/bsdf.h"
#include "scene/camera.h"
#include "scene/lights.h"
#include "scene/scene.h"
#include "trace/trace.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct batch {
    il_ray *closest;   /* camera + bounce rays */
    size_t num_closest;
    il_ray *shadow;
    size_t num_shadow;
} batch;

/* Follows one path per pixel the way the path tracer does (camera ray, then
 * per vertex a shadow ray to a sampled light point and a BSDF-sampled bounce,
 * Russian roulette after the third bounce, at most 8 bounces) and records
 * every ray it casts: the batch has the path tracer's own mix of coherent
 * and incoherent rays. */
static void make_batch(const il_scene *scene, uint32_t w, uint32_t h, batch *b)
{
    size_t cap_c = (size_t)w * h * 4, cap_s = (size_t)w * h * 4;
    b->closest = malloc(cap_c * sizeof(il_ray));
    b->shadow = malloc(cap_s * sizeof(il_ray));
    b->num_closest = b->num_shadow = 0;
    il_camera cam;
    il_camera_desc cd;
    il_scene_get_camera(scene, &cd);
    il_camera_init(&cam, &cd, w, h);
    il_pcg32 rng = il_pcg32_seed(1, 2);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            il_ray ray = {.org = cam.position, .tmin = 0.0f, .tmax = INFINITY,
                          .dir = il_camera_ray_dir(&cam, x + il_pcg32_float(&rng), y + il_pcg32_float(&rng))};
            il_vec3 beta = v3s(1.0f);
            for (int depth = 0; depth < 9; depth++) {
                if (b->num_closest == cap_c) {
                    cap_c *= 2;
                    b->closest = realloc(b->closest, cap_c * sizeof(il_ray));
                }
                b->closest[b->num_closest++] = ray;
                il_hit hit;
                if (!il_trace_closest(scene->tracer, &ray, &hit) || depth == 8)
                    break;
                il_surface s;
                il_scene_surface(scene, hit.mesh, hit.prim, hit.b1, hit.b2, &s);
                il_bsdf bsdf;
                il_bsdf_init(&bsdf, scene, &s);
                il_vec3 wo = v3_neg(ray.dir);
                il_light_sample ls;
                if (!il_bsdf_is_delta(&bsdf) &&
                    il_light_sample_at(scene, s.p, il_pcg32_float(&rng),
                                       v2(il_pcg32_float(&rng), il_pcg32_float(&rng)), &ls)) {
                    if (b->num_shadow == cap_s) {
                        cap_s *= 2;
                        b->shadow = realloc(b->shadow, cap_s * sizeof(il_ray));
                    }
                    if (isfinite(ls.dist))
                        b->shadow[b->num_shadow++] = il_shadow_ray(scene->tracer, s.p, s.ng, ls.p, ls.n);
                    else
                        b->shadow[b->num_shadow++] = (il_ray){
                            .org = il_offset_origin(scene->tracer, s.p, s.ng, ls.wi), .dir = ls.wi,
                            .tmin = 0.0f, .tmax = INFINITY};
                }
                il_bsdf_sample bs;
                if (!il_bsdf_sample_dir(&bsdf, wo, il_pcg32_float(&rng),
                                        v2(il_pcg32_float(&rng), il_pcg32_float(&rng)), &bs))
                    break;
                beta = v3_mul(beta, bs.weight);
                if (depth >= 3) {
                    float q = fminf(v3_max_comp(beta), 0.95f);
                    if (!(il_pcg32_float(&rng) < q))
                        break;
                    beta = v3_scale(beta, 1.0f / q);
                }
                ray = (il_ray){.org = il_offset_origin(scene->tracer, s.p, s.ng, bs.wi), .dir = bs.wi,
                               .tmin = 0.0f, .tmax = INFINITY};
            }
        }
}

/* Embree alone: a device and scene of our own, the same geometry. */
static RTCScene embree_scene(RTCDevice dev, const il_scene *scene)
{
    RTCScene s = rtcNewScene(dev);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    for (uint32_t i = 0; i < scene->num_meshes; i++) {
        const il_mesh *m = &scene->meshes[i];
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, m->positions, 0,
                                   sizeof(il_vec3), m->num_vertices);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->indices, 0,
                                   3 * sizeof(uint32_t), m->num_triangles);
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(s, g, i);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(s);
    return s;
}

enum { CHUNK = 256 };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double time_embree(RTCScene s, const batch *b, int threads, unsigned *checksum)
{
    unsigned sum = 0;
    double t0 = now();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 16) reduction(+ : sum)
    for (size_t i = 0; i < b->num_closest; i++) {
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        const il_ray *r = &b->closest[i];
        struct RTCRayHit rh = {
            .ray = {r->org.x, r->org.y, r->org.z, r->tmin, r->dir.x, r->dir.y, r->dir.z, 0.0f,
                    r->tmax, 0xffffffffu, 0, 0},
            .hit = {.geomID = RTC_INVALID_GEOMETRY_ID, .instID = {RTC_INVALID_GEOMETRY_ID}}};
        rtcIntersect1(s, &ctx, &rh);
        sum += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
#pragma omp parallel for num_threads(threads) schedule(dynamic, 16) reduction(+ : sum)
    for (size_t i = 0; i < b->num_shadow; i++) {
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        const il_ray *r = &b->shadow[i];
        struct RTCRay ray = {r->org.x, r->org.y, r->org.z, r->tmin, r->dir.x, r->dir.y, r->dir.z,
                             0.0f, r->tmax, 0xffffffffu, 0, 0};
        rtcOccluded1(s, &ctx, &ray);
        sum += ray.tfar < 0.0f;
    }
    *checksum = sum;
    return now() - t0;
}

static double time_wrapper(const il_tracer *t, const batch *b, int threads, unsigned *checksum)
{
    unsigned sum = 0;
    double t0 = now();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 16) reduction(+ : sum)
    for (size_t i = 0; i < b->num_closest; i++) {
        il_hit hit;
        sum += il_trace_closest(t, &b->closest[i], &hit);
    }
#pragma omp parallel for num_threads(threads) schedule(dynamic, 16) reduction(+ : sum)
    for (size_t i = 0; i < b->num_shadow; i++)
        sum += il_trace_occluded(t, &b->shadow[i]);
    *checksum = sum;
    return now() - t0;
}

static double time_streams(const il_tracer *t, const batch *b, int threads, unsigned *checksum)
{
    unsigned sum = 0;
    double t0 = now();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : sum)
    for (size_t c = 0; c < b->num_closest; c += CHUNK) {
        il_hit hits[CHUNK];
        size_t m = b->num_closest - c < CHUNK ? b->num_closest - c : CHUNK;
        il_trace_closest_n(t, b->closest + c, hits, m);
        for (size_t i = 0; i < m; i++)
            sum += hits[i].mesh != IL_HIT_NONE;
    }
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : sum)
    for (size_t c = 0; c < b->num_shadow; c += CHUNK) {
        bool occ[CHUNK];
        size_t m = b->num_shadow - c < CHUNK ? b->num_shadow - c : CHUNK;
        il_trace_occluded_n(t, b->shadow + c, occ, m);
        for (size_t i = 0; i < m; i++)
            sum += occ[i];
    }
    *checksum = sum;
    return now() - t0;
}

int main(int argc, char **argv)
{
    const char *name = "cornell";
    uint32_t w = 512, h = 512, spp = 16;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--width") && i + 1 < argc)
            w = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--height") && i + 1 < argc)
            h = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--spp") && i + 1 < argc)
            spp = (uint32_t)atoi(argv[++i]);
        else
            name = argv[i];
    }
    il_error err = {0};
    il_scene *scene = NULL;
    if (il_scene_load(name, NULL, &scene, &err) != IL_OK || il_scene_commit(scene, &err) != IL_OK) {
        fprintf(stderr, "bench_rays: %s\n", err.message);
        return 1;
    }
    batch b;
    make_batch(scene, w, h, &b);
    size_t total = b.num_closest + b.num_shadow;
    printf("scene %s: %zu closest-hit rays (camera + bounces), %zu shadow rays\n", name,
           b.num_closest, b.num_shadow);

    RTCDevice dev = rtcNewDevice("verbose=0");
    RTCScene es = embree_scene(dev, scene);
    double embree_best[3] = {0};
    printf("%-28s %8s %14s\n", "caster", "threads", "Mrays/s");
    for (int threads = 1; threads <= 2; threads++) {
        unsigned c1, c2, c3;
        const int reps = 3;
        double te = 1e30, tw = 1e30, ts = 1e30;
        for (int r = 0; r < reps; r++) { /* best of three: the machine is shared */
            double t;
            if ((t = time_embree(es, &b, threads, &c1)) < te) te = t;
            if ((t = time_wrapper(scene->tracer, &b, threads, &c2)) < tw) tw = t;
            if ((t = time_streams(scene->tracer, &b, threads, &c3)) < ts) ts = t;
        }
        if (c1 != c2 || c1 != c3)
            printf("warning: hit counts differ: embree %u, wrapper %u, streams %u\n", c1, c2, c3);
        embree_best[threads] = total / te;
        printf("%-28s %8d %14.2f\n", "Embree rtcIntersect1 alone", threads, total / te * 1e-6);
        printf("%-28s %8d %14.2f\n", "il_trace_closest/occluded", threads, total / tw * 1e-6);
        printf("%-28s %8d %14.2f\n", "il_trace_*_n streams", threads, total / ts * 1e-6);
    }
    /* The path tracer's share of Embree's rate, two ways, as the machine's
     * speed drifts: its best rate over Embree's best (the casters' three
     * runs and the five below), and the median and range of five pairs,
     * each render against an Embree-alone run just before it. */
    il_film *film = NULL;
    il_film_create(w, h, &film, &err);
    for (int threads = 1; threads <= 2; threads++) {
        il_render_desc rd = {.spp = spp, .max_depth = 8, .threads = threads};
        enum { PAIRS = 5 };
        double share[PAIRS], rate = 0.0, seconds = 0.0, best_alone = embree_best[threads];
        for (int r = 0; r < PAIRS; r++) {
            unsigned c;
            double alone = total / time_embree(es, &b, threads, &c);
            if (alone > best_alone)
                best_alone = alone;
            il_render_stats st;
            if (il_render(scene, film, &rd, &st, &err) != IL_OK) {
                fprintf(stderr, "bench_rays: %s\n", err.message);
                return 1;
            }
            share[r] = st.rays / st.seconds / alone;
            if (st.rays / st.seconds > rate) {
                rate = st.rays / st.seconds;
                seconds = st.seconds / st.spp;
            }
        }
        qsort(share, PAIRS, sizeof share[0], cmp_double);
        printf("%-28s %8d %14.2f   (%.0f%% of Embree alone's best; paired: median %.0f%%, range "
               "%.0f-%.0f%%; %.3f Msamples/s)\n",
               "path tracer (depth 8)", threads, rate * 1e-6, 100.0 * rate / best_alone,
               100.0 * share[PAIRS / 2], 100.0 * share[0], 100.0 * share[PAIRS - 1],
               (double)w * h / seconds * 1e-6);
    }
    il_film_release(film);
    rtcReleaseScene(es);
    rtcReleaseDevice(dev);
    free(b.closest);
    free(b.shadow);
    il_scene_release(scene);
    return 0;
}
