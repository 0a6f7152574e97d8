/* Rays per second: Embree alone vs the il_trace wrappers vs the path tracer.
 *
 *   bench_rays [SCENE] [--width W] [--height H] [--spp N]
 *
 * Builds one batch of rays with the path tracer's mix (camera rays, cosine
 * bounce rays from the first hits, shadow rays to sampled light points), then
 * times the same batch cast (a) by Embree directly (rtcIntersect1/rtcOccluded1
 * on a scene built here), (b) through il_trace_closest/occluded, (c) through
 * the stream calls, each with 1 and 2 threads; last it renders the scene with
 * the path tracer (max depth 8) and reports its rays/s and its share of
 * Embree's own rate.  It prints figures and never judges them. */
#include <embree3/rtcore.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/rng.h"
#include "core/sampling.h"
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

static void make_batch(const il_scene *scene, uint32_t w, uint32_t h, batch *b)
{
    size_t n = (size_t)w * h;
    b->closest = malloc(2 * n * sizeof(il_ray));
    b->shadow = malloc(n * sizeof(il_ray));
    il_hit *hits = malloc(n * sizeof(il_hit));
    il_camera cam;
    il_camera_desc cd;
    il_scene_get_camera(scene, &cd);
    il_camera_init(&cam, &cd, w, h);
    il_pcg32 rng = il_pcg32_seed(1, 2);
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            il_ray *r = &b->closest[(size_t)y * w + x];
            r->org = cam.position;
            r->dir = il_camera_ray_dir(&cam, x + il_pcg32_float(&rng), y + il_pcg32_float(&rng));
            r->tmin = 0.0f;
            r->tmax = INFINITY;
        }
    il_trace_closest_n(scene->tracer, b->closest, hits, n);
    size_t nc = n, ns = 0;
    for (size_t i = 0; i < n; i++) {
        if (hits[i].mesh == IL_HIT_NONE)
            continue;
        il_surface s;
        il_scene_surface(scene, hits[i].mesh, hits[i].prim, hits[i].b1, hits[i].b2, &s);
        il_vec3 wo = v3_neg(b->closest[i].dir);
        il_vec3 n_side = v3_dot(s.ng, wo) < 0.0f ? v3_neg(s.ng) : s.ng;
        il_frame f = il_frame_from_normal(n_side);
        il_vec2 u = v2(il_pcg32_float(&rng), il_pcg32_float(&rng));
        il_vec3 d = il_frame_to_world(&f, il_sample_cosine_hemisphere(u));
        il_ray *br = &b->closest[nc++];
        br->org = il_offset_origin(scene->tracer, s.p, s.ng, d);
        br->dir = d;
        br->tmin = 0.0f;
        br->tmax = INFINITY;
        il_light_sample ls;
        if (il_light_sample_at(scene, s.p, il_pcg32_float(&rng),
                               v2(il_pcg32_float(&rng), il_pcg32_float(&rng)), &ls)) {
            if (isfinite(ls.dist)) {
                b->shadow[ns++] = il_shadow_ray(scene->tracer, s.p, s.ng, ls.p, ls.n);
            } else {
                il_ray *sr = &b->shadow[ns++];
                sr->org = il_offset_origin(scene->tracer, s.p, s.ng, ls.wi);
                sr->dir = ls.wi;
                sr->tmin = 0.0f;
                sr->tmax = INFINITY;
            }
        }
    }
    b->num_closest = nc;
    b->num_shadow = ns;
    free(hits);
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
    printf("scene %s: %zu closest-hit rays (camera + bounce), %zu shadow rays\n", name,
           b.num_closest, b.num_shadow);

    RTCDevice dev = rtcNewDevice("verbose=0");
    RTCScene es = embree_scene(dev, scene);
    double embree_rate[3] = {0};
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
        embree_rate[threads] = total / te;
        printf("%-28s %8d %14.2f\n", "Embree rtcIntersect1 alone", threads, total / te * 1e-6);
        printf("%-28s %8d %14.2f\n", "il_trace_closest/occluded", threads, total / tw * 1e-6);
        printf("%-28s %8d %14.2f\n", "il_trace_*_n streams", threads, total / ts * 1e-6);
    }
    rtcReleaseScene(es);
    rtcReleaseDevice(dev);

    il_film *film = NULL;
    il_film_create(w, h, &film, &err);
    for (int threads = 1; threads <= 2; threads++) {
        il_render_desc rd = {.spp = spp, .max_depth = 8, .threads = threads};
        il_render_stats st;
        if (il_render(scene, film, &rd, &st, &err) != IL_OK) {
            fprintf(stderr, "bench_rays: %s\n", err.message);
            return 1;
        }
        double rate = st.rays / st.seconds;
        printf("%-28s %8d %14.2f   (%.0f%% of Embree alone; %.3f Msamples/s)\n",
               "path tracer (depth 8)", threads, rate * 1e-6, 100.0 * rate / embree_rate[threads],
               (double)w * h * st.spp / st.seconds * 1e-6);
    }
    il_film_release(film);
    free(b.closest);
    free(b.shadow);
    il_scene_release(scene);
    return 0;
}
