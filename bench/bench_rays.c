/* Rays per second: Embree alone vs the il_trace wrappers vs the path tracer.
 *
 *   bench_rays [SCENE] [--width W] [--height H] [--spp N]
 *
 * Records the rays the path tracer itself casts in one pass of one sample
 * per pixel (max depth 8, one thread), batch by batch as it hands them to
 * the ray core: every call of il_trace_closest_n(_coherent) and
 * il_trace_occluded_n, caught by the linker (-Wl,--wrap, bench/CMakeLists.txt).
 * Then it times the same batches, in the same order, cast (a) by Embree
 * directly (rtcIntersect1/rtcOccluded1 ray by ray on a scene built here),
 * (b) through il_trace_closest/occluded, (c) through the stream calls, each
 * with 1 and 2 threads (best of three; two threads take whole batches).
 * Last it renders the scene with the path tracer (max depth 8, N samples
 * per pixel) five times, each right after an Embree-alone run, and reports
 * its best rays/s and its share of Embree's own rate: best over best, and
 * the median of the five pairs' ratios.  It prints figures and never
 * judges them. */
#include <embree3/rtcore.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scene/scene.h"
#include "trace/trace.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef enum { CLOSEST, CLOSEST_COHERENT, OCCLUDED } batch_kind;

/* One call of the path tracer's: rays[start .. start+n-1]. */
typedef struct batch {
    size_t start, n;
    batch_kind kind;
} batch;

typedef struct recording {
    il_ray *rays;
    size_t num_rays, cap_rays;
    batch *batches;
    size_t num_batches, cap_batches;
    size_t per_kind[3];
} recording;

/* Set only while the recording render runs, on one thread. */
static recording *g_rec;

static void grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return;
    size_t c = *cap ? *cap : 1024;
    while (c < need)
        c *= 2;
    void *q = realloc(*p, c * size);
    if (!q) {
        fprintf(stderr, "bench_rays: out of memory recording the rays\n");
        exit(1);
    }
    *p = q;
    *cap = c;
}

static void record(const il_ray *rays, size_t n, batch_kind kind)
{
    recording *r = g_rec;
    if (!r || n == 0)
        return;
    grow((void **)&r->rays, &r->cap_rays, r->num_rays + n, sizeof(il_ray));
    grow((void **)&r->batches, &r->cap_batches, r->num_batches + 1, sizeof(batch));
    r->batches[r->num_batches++] = (batch){.start = r->num_rays, .n = n, .kind = kind};
    memcpy(r->rays + r->num_rays, rays, n * sizeof(il_ray));
    r->num_rays += n;
    r->per_kind[kind] += n;
}

/* The linker sends the library's calls of these here (--wrap). */
void __real_il_trace_closest_n(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n);
void __real_il_trace_closest_n_coherent(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n);
void __real_il_trace_occluded_n(const il_tracer *t, const il_ray *rays, bool *occluded, size_t n);
bool __real_il_trace_closest(const il_tracer *t, const il_ray *ray, il_hit *hit);
bool __real_il_trace_occluded(const il_tracer *t, const il_ray *ray);
void __wrap_il_trace_closest_n(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n);
void __wrap_il_trace_closest_n_coherent(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n);
void __wrap_il_trace_occluded_n(const il_tracer *t, const il_ray *rays, bool *occluded, size_t n);
bool __wrap_il_trace_closest(const il_tracer *t, const il_ray *ray, il_hit *hit);
bool __wrap_il_trace_occluded(const il_tracer *t, const il_ray *ray);

void __wrap_il_trace_closest_n(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n)
{
    record(rays, n, CLOSEST);
    __real_il_trace_closest_n(t, rays, hits, n);
}

void __wrap_il_trace_closest_n_coherent(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n)
{
    record(rays, n, CLOSEST_COHERENT);
    __real_il_trace_closest_n_coherent(t, rays, hits, n);
}

void __wrap_il_trace_occluded_n(const il_tracer *t, const il_ray *rays, bool *occluded, size_t n)
{
    record(rays, n, OCCLUDED);
    __real_il_trace_occluded_n(t, rays, occluded, n);
}

bool __wrap_il_trace_closest(const il_tracer *t, const il_ray *ray, il_hit *hit)
{
    record(ray, 1, CLOSEST);
    return __real_il_trace_closest(t, ray, hit);
}

bool __wrap_il_trace_occluded(const il_tracer *t, const il_ray *ray)
{
    record(ray, 1, OCCLUDED);
    return __real_il_trace_occluded(t, ray);
}

/* One pass of the path tracer at one sample per pixel, its rays kept. */
static bool record_pass(const il_scene *scene, uint32_t w, uint32_t h, recording *rec)
{
    il_error err = {0};
    il_film *film = NULL;
    if (il_film_create(w, h, &film, &err) != IL_OK) {
        fprintf(stderr, "bench_rays: %s\n", err.message);
        return false;
    }
    il_render_desc rd = {.spp = 1, .max_depth = 8, .threads = 1};
    il_render_stats st;
    g_rec = rec;
    il_status s = il_render(scene, film, &rd, &st, &err);
    g_rec = NULL;
    il_film_release(film);
    if (s != IL_OK) {
        fprintf(stderr, "bench_rays: %s\n", err.message);
        return false;
    }
    if (rec->num_rays == 0) {
        /* The calls inside a shared libillum do not reach the wrappers. */
        fprintf(stderr, "bench_rays: no ray was recorded (bench_rays needs the static libillum)\n");
        return false;
    }
    if ((double)rec->num_rays != (double)st.rays)
        printf("warning: %zu rays recorded, the path tracer counted %.0f\n", rec->num_rays,
               (double)st.rays);
    return true;
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

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void to_rtc(const il_ray *r, struct RTCRay *o)
{
    *o = (struct RTCRay){r->org.x, r->org.y, r->org.z, r->tmin, r->dir.x, r->dir.y, r->dir.z,
                         0.0f, r->tmax, 0xffffffffu, 0, 0};
}

/* Each caster takes the batches in the recorded order, whole batches per
 * thread; sum counts the hits, which must agree between casters. */
static double time_embree(RTCScene s, const recording *rec, int threads, unsigned *checksum)
{
    unsigned sum = 0;
    double t0 = now();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : sum)
    for (size_t b = 0; b < rec->num_batches; b++) {
        const batch *bt = &rec->batches[b];
        for (size_t i = bt->start; i < bt->start + bt->n; i++) {
            struct RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            if (bt->kind == OCCLUDED) {
                struct RTCRay ray;
                to_rtc(&rec->rays[i], &ray);
                rtcOccluded1(s, &ctx, &ray);
                sum += ray.tfar < 0.0f;
            } else {
                struct RTCRayHit rh;
                to_rtc(&rec->rays[i], &rh.ray);
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(s, &ctx, &rh);
                sum += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            }
        }
    }
    *checksum = sum;
    return now() - t0;
}

static double time_wrapper(const il_tracer *t, const recording *rec, int threads, unsigned *checksum)
{
    unsigned sum = 0;
    double t0 = now();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : sum)
    for (size_t b = 0; b < rec->num_batches; b++) {
        const batch *bt = &rec->batches[b];
        for (size_t i = bt->start; i < bt->start + bt->n; i++) {
            il_hit hit;
            sum += bt->kind == OCCLUDED ? il_trace_occluded(t, &rec->rays[i])
                                        : il_trace_closest(t, &rec->rays[i], &hit);
        }
    }
    *checksum = sum;
    return now() - t0;
}

enum { MAX_BATCH = 4096 };

static double time_streams(const il_tracer *t, const recording *rec, int threads, unsigned *checksum)
{
    unsigned sum = 0;
    double t0 = now();
#pragma omp parallel num_threads(threads) reduction(+ : sum)
    {
        il_hit *hits = malloc(MAX_BATCH * sizeof *hits);
        bool *occ = malloc(MAX_BATCH * sizeof *occ);
        if (!hits || !occ) {
            fprintf(stderr, "bench_rays: out of memory\n");
            exit(1);
        }
#pragma omp for schedule(dynamic, 1)
        for (size_t b = 0; b < rec->num_batches; b++) {
            const batch *bt = &rec->batches[b];
            for (size_t c = 0; c < bt->n; c += MAX_BATCH) {
                size_t m = bt->n - c < MAX_BATCH ? bt->n - c : MAX_BATCH;
                const il_ray *rays = rec->rays + bt->start + c;
                if (bt->kind == OCCLUDED) {
                    il_trace_occluded_n(t, rays, occ, m);
                    for (size_t i = 0; i < m; i++)
                        sum += occ[i];
                } else {
                    if (bt->kind == CLOSEST_COHERENT)
                        il_trace_closest_n_coherent(t, rays, hits, m);
                    else
                        il_trace_closest_n(t, rays, hits, m);
                    for (size_t i = 0; i < m; i++)
                        sum += hits[i].mesh != IL_HIT_NONE;
                }
            }
        }
        free(hits);
        free(occ);
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
    recording rec = {0};
    if (!record_pass(scene, w, h, &rec))
        return 1;
    size_t total = rec.num_rays;
    printf("scene %s: the path tracer's rays of one sample per pixel: %zu camera, %zu other "
           "closest-hit, %zu shadow, in %zu batches\n",
           name, rec.per_kind[CLOSEST_COHERENT], rec.per_kind[CLOSEST], rec.per_kind[OCCLUDED],
           rec.num_batches);

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
            if ((t = time_embree(es, &rec, threads, &c1)) < te) te = t;
            if ((t = time_wrapper(scene->tracer, &rec, threads, &c2)) < tw) tw = t;
            if ((t = time_streams(scene->tracer, &rec, threads, &c3)) < ts) ts = t;
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
            double alone = total / time_embree(es, &rec, threads, &c);
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
    free(rec.rays);
    free(rec.batches);
    il_scene_release(scene);
    return 0;
}
