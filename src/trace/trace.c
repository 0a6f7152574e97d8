/* Embree 3 behind the il_tracer interface. */
#include "trace/trace.h"

#include <embree3/rtcore.h>
#include <float.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "scene/pane.h"
#include "scene/scene.h"

/* The panes of one Embree geometry, its user data: one pane for all its
 * triangles (a scene mesh) or one per triangle (il_tracer_create_triangles_panes,
 * where ior 0 marks a triangle that is not a pane). */
typedef struct pane_geom {
    il_trace_pane one;
    const il_trace_pane *per_triangle;
} pane_geom;

struct il_tracer {
    RTCDevice device;
    RTCScene scene;
    float epsilon;
    pane_geom *panes;        /* one per mesh; used by the geometries with panes */
    bool has_panes;          /* some geometry has pane_filter */
    char embree_error[256];  /* first error Embree reported while building */
};

/* What a query does at a pane (pane_filter). */
typedef enum pane_mode {
    PANE_DRAW,        /* closest hit: pass with probability T */
    PANE_CLEAR,       /* il_trace_occluded: pass */
    PANE_WEIGH        /* il_trace_visibility: pass, multiplying the ray's visibility by T */
} pane_mode;

enum { STREAM_CHUNK = 256, PANES_MET = 4 };

/* A pane crossing a ray made: the geometry, the distance, the outcome.
 * Embree may report a triangle twice (RTC_BUILD_QUALITY_HIGH), and a ray
 * through the edge between two triangles of a surface meets both at one
 * distance (rtcSetGeometryIntersectFilterFunction's manual): a report at
 * the distance of an earlier one is the same crossing and gets its outcome,
 * so no crossing is drawn or weighed twice. */
typedef struct pane_met {
    uint32_t geom;
    float t;
    bool passed;
} pane_met;

/* Every query's context: Embree's, what panes do, and per ray (by the ray's
 * id) its last crossings and, for PANE_WEIGH, its visibility. */
typedef struct query_ctx {
    struct RTCIntersectContext rtc;
    pane_mode mode;
    float *vis;
    pane_met (*met)[PANES_MET];
    uint32_t *num_met;
} query_ctx;

/* A chunk of up to STREAM_CHUNK rays' crossings. */
typedef struct pane_log {
    pane_met met[STREAM_CHUNK][PANES_MET];
    uint32_t num_met[STREAM_CHUNK];
} pane_log;

/* met and num_met: the crossings' log of the query's rays (NULL for
 * PANE_CLEAR, which logs none). */
static void query_init(query_ctx *q, enum RTCIntersectContextFlags flags, pane_mode mode,
                       pane_met (*met)[PANES_MET], uint32_t *num_met)
{
    rtcInitIntersectContext(&q->rtc);
    q->rtc.flags = flags;
    q->mode = mode;
    q->vis = NULL;
    q->met = met;
    q->num_met = num_met;
}

static const pane_met *met_before(const query_ctx *q, uint32_t k, uint32_t geom, float t)
{
    uint32_t n = q->num_met[k];
    for (uint32_t j = 0; j < n && j < PANES_MET; j++) {
        const pane_met *m = &q->met[k][j];
        if (m->geom == geom && fabsf(m->t - t) <= 1e-5f * fmaxf(t, 1e-3f))
            return m;
    }
    return NULL;
}

static void remember(const query_ctx *q, uint32_t k, uint32_t geom, float t, bool passed)
{
    uint32_t n = q->num_met[k];
    q->met[k][n % PANES_MET] = (pane_met){.geom = geom, .t = t, .passed = passed}; /* a ring */
    q->num_met[k] = n + 1;
}

/* A number in [0, 1) that is a function of the ray and the triangle only
 * (a chain of 32-bit integer hashes, Jarzynski & Olano 2020's PCG hash):
 * the same ray meets the same pane with the same outcome in any thread. */
static uint32_t hash_u32(uint32_t v)
{
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

static float pane_number(const float *ray, unsigned N, unsigned i, uint32_t geom, uint32_t prim)
{
    uint32_t h = hash_u32(geom * 0x9e3779b9u ^ prim);
    static const unsigned fields[6] = {0, 1, 2, 4, 5, 6};   /* org, dir (RTCRayN rows) */
    for (int k = 0; k < 6; k++) {
        uint32_t bits;
        memcpy(&bits, &ray[fields[k] * N + i], sizeof bits);
        h = hash_u32(h ^ bits);
    }
    return (float)(h >> 8) * 0x1p-24f;
}

/* The filter of a geometry with panes.  Light passes a pane on a straight
 * line, so no method needs a vertex there: a closest-hit ray passes it with
 * the pane's transmittance T at the ray's incidence (scene/pane.h), and a
 * ray not let through stops at the pane, whose BSDF reflects (bsdf.c,
 * pane_sample); an occlusion ray passes it, weighed by T for
 * il_trace_visibility.  The RTCRayN/RTCHitN layouts are those of Embree's
 * rtcore_ray.h accessors, which are C++ only; the hit's distance is the
 * ray's tfar. */
static void pane_filter(const struct RTCFilterFunctionNArguments *args)
{
    const pane_geom *g = args->geometryUserPtr;
    const query_ctx *q = (const query_ctx *)args->context;
    const float *ray = (const float *)args->ray, *hit = (const float *)args->hit;
    unsigned N = args->N;
    for (unsigned i = 0; i < N; i++) {
        if (args->valid[i] != -1)
            continue;
        uint32_t prim, geom, id;
        memcpy(&prim, &hit[5 * N + i], sizeof prim);
        memcpy(&geom, &hit[6 * N + i], sizeof geom);
        const il_trace_pane *p = g->per_triangle ? &g->per_triangle[prim] : &g->one;
        if (!(p->ior > 0.0f))
            continue;                   /* not a pane: the hit stands */
        if (q->mode == PANE_CLEAR) {
            args->valid[i] = 0;
            continue;
        }
        memcpy(&id, &ray[10 * N + i], sizeof id);
        float t = ray[8 * N + i];
        const pane_met *before = met_before(q, id, geom, t);
        if (before) {
            if (before->passed)
                args->valid[i] = 0;
            continue;
        }
        float d[3] = {ray[4 * N + i], ray[5 * N + i], ray[6 * N + i]};
        float n[3] = {hit[0 * N + i], hit[1 * N + i], hit[2 * N + i]};
        float dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        float dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        float R, T = 0.0f;
        if (dd > 0.0f && nn > 0.0f)
            il_pane_optics(p->ior, p->tau, fabsf(dn) / sqrtf(dd * nn), &R, &T);
        bool pass = true;
        if (q->mode == PANE_WEIGH)
            q->vis[id] *= T;
        else
            pass = pane_number(ray, N, i, geom, prim) < T;
        remember(q, id, geom, t, pass);
        if (pass)
            args->valid[i] = 0;
    }
}

static void on_embree_error(void *user, enum RTCError code, const char *str)
{
    il_tracer *t = user;
    if (t->embree_error[0] == '\0')
        snprintf(t->embree_error, sizeof t->embree_error, "Embree error %d: %s", (int)code,
                 str ? str : "");
}

/* One triangle geometry over shared arrays: Embree reads them in place.
 * Vertex buffers need 4 bytes of padding after the last element (Embree
 * docs); callers allocate it (il_scene_add_mesh does). */
static void attach_triangles(il_tracer *t, const il_vec3 *positions, uint32_t num_vertices,
                             const uint32_t *indices, uint32_t num_triangles, uint32_t id,
                             const pane_geom *glass)
{
    RTCGeometry g = rtcNewGeometry(t->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions, 0,
                               sizeof(il_vec3), num_vertices);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0,
                               3 * sizeof(uint32_t), num_triangles);
    if (glass) {
        t->has_panes = true;
        rtcSetGeometryUserData(g, (void *)glass);
        rtcSetGeometryIntersectFilterFunction(g, pane_filter);
        rtcSetGeometryOccludedFilterFunction(g, pane_filter);
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(t->scene, g, id);
    rtcReleaseGeometry(g);
}

static il_status begin(il_tracer **out, il_error *err)
{
    *out = NULL;
    il_tracer *t = il_calloc(1, sizeof *t, err);
    if (!t)
        return IL_ERR_MEMORY;
    t->device = rtcNewDevice("verbose=0");
    if (!t->device) {
        free(t);
        return il_fail(err, IL_ERR_RUNTIME, "could not create the Embree device (error %d)",
                       (int)rtcGetDeviceError(NULL));
    }
    rtcSetDeviceErrorFunction(t->device, on_embree_error, t);
    t->scene = rtcNewScene(t->device);
    rtcSetSceneBuildQuality(t->scene, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(t->scene, RTC_SCENE_FLAG_ROBUST);
    *out = t;
    return IL_OK;
}

static il_status finish(il_tracer *t, il_tracer **out, il_error *err)
{
    rtcCommitScene(t->scene);
    if (t->embree_error[0]) {
        il_fail(err, IL_ERR_RUNTIME, "building the ray-casting structure failed: %s",
                t->embree_error);
        il_tracer_release(t);
        *out = NULL;
        return IL_ERR_RUNTIME;
    }

    /* Offsets: 1e-5 of the scene's extent plus a relative term for points far
     * from the origin, where float spacing grows. */
    struct RTCBounds b;
    rtcGetSceneBounds(t->scene, &b);
    float extent = il_maxf(il_maxf(b.upper_x - b.lower_x, b.upper_y - b.lower_y), b.upper_z - b.lower_z);
    if (!(extent > 0.0f) || !isfinite(extent))
        extent = 1.0f;
    t->epsilon = 1e-5f * extent;
    *out = t;
    return IL_OK;
}

il_status il_tracer_create(const il_scene *scene, il_tracer **out, il_error *err)
{
    il_tracer *t;
    il_status st = begin(&t, err);
    if (st != IL_OK)
        return st;
    t->panes = il_calloc(scene->num_meshes ? scene->num_meshes : 1, sizeof(pane_geom), err);
    if (!t->panes) {
        il_tracer_release(t);
        return IL_ERR_MEMORY;
    }
    for (uint32_t i = 0; i < scene->num_meshes; i++) {
        const il_mesh *m = &scene->meshes[i];
        const il_material *mat = &scene->materials[m->material];
        pane_geom *glass = NULL;
        if (mat->type == IL_MATERIAL_THIN_GLASS) {
            glass = &t->panes[i];
            glass->one = (il_trace_pane){.ior = mat->ior, .tau = mat->pane_tau};
        }
        attach_triangles(t, m->positions, m->num_vertices, m->indices, m->num_triangles, i, glass);
    }
    return finish(t, out, err);
}

il_status il_tracer_create_triangles_panes(const il_vec3 *positions, uint32_t num_vertices,
                                           const uint32_t *indices, uint32_t num_triangles,
                                           const il_trace_pane *panes, il_tracer **out,
                                           il_error *err)
{
    il_tracer *t;
    il_status st = begin(&t, err);
    if (st != IL_OK)
        return st;
    if (panes) {
        t->panes = il_calloc(1, sizeof(pane_geom), err);
        if (!t->panes) {
            il_tracer_release(t);
            return IL_ERR_MEMORY;
        }
        t->panes->per_triangle = panes;
    }
    attach_triangles(t, positions, num_vertices, indices, num_triangles, 0, t->panes);
    return finish(t, out, err);
}

il_status il_tracer_create_triangles(const il_vec3 *positions, uint32_t num_vertices,
                                     const uint32_t *indices, uint32_t num_triangles,
                                     il_tracer **out, il_error *err)
{
    return il_tracer_create_triangles_panes(positions, num_vertices, indices, num_triangles, NULL,
                                            out, err);
}

void il_tracer_release(il_tracer *t)
{
    if (!t)
        return;
    if (t->scene)
        rtcReleaseScene(t->scene);
    if (t->device)
        rtcReleaseDevice(t->device);
    free(t->panes);
    free(t);
}

static inline void to_rtc_ray(const il_ray *r, struct RTCRay *o)
{
    o->org_x = r->org.x;
    o->org_y = r->org.y;
    o->org_z = r->org.z;
    o->tnear = r->tmin;
    o->dir_x = r->dir.x;
    o->dir_y = r->dir.y;
    o->dir_z = r->dir.z;
    o->time = 0.0f;
    o->tfar = r->tmax;
    o->mask = 0xffffffffu;
    o->id = 0;
    o->flags = 0;
}

static inline bool from_rtc_hit(const struct RTCRayHit *rh, il_hit *hit)
{
    if (rh->hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        hit->mesh = IL_HIT_NONE;
        return false;
    }
    hit->t = rh->ray.tfar;
    hit->mesh = rh->hit.geomID;
    hit->prim = rh->hit.primID;
    hit->b1 = rh->hit.u;
    hit->b2 = rh->hit.v;
    hit->ng = v3(rh->hit.Ng_x, rh->hit.Ng_y, rh->hit.Ng_z);
    return true;
}

/* One ray's crossings: its own log entry (id 0). */
typedef struct pane_log1 {
    pane_met met[1][PANES_MET];
    uint32_t num_met[1];
} pane_log1;

bool il_trace_closest(const il_tracer *t, const il_ray *ray, il_hit *hit)
{
    pane_log1 log = {.num_met = {0}};
    query_ctx ctx;
    query_init(&ctx, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, PANE_DRAW, log.met, log.num_met);
    struct RTCRayHit rh;
    to_rtc_ray(ray, &rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(t->scene, &ctx.rtc, &rh);
    return from_rtc_hit(&rh, hit);
}

bool il_trace_occluded(const il_tracer *t, const il_ray *ray)
{
    query_ctx ctx;
    query_init(&ctx, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, PANE_CLEAR, NULL, NULL);
    struct RTCRay r;
    to_rtc_ray(ray, &r);
    rtcOccluded1(t->scene, &ctx.rtc, &r);
    return r.tfar < 0.0f; /* Embree sets tfar to -inf on a hit */
}

float il_trace_visibility(const il_tracer *t, const il_ray *ray)
{
    pane_log1 log = {.num_met = {0}};
    float vis = 1.0f;
    query_ctx ctx;
    query_init(&ctx, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, PANE_WEIGH, log.met, log.num_met);
    ctx.vis = &vis;
    struct RTCRay r;
    to_rtc_ray(ray, &r);
    rtcOccluded1(t->scene, &ctx.rtc, &r);
    return r.tfar < 0.0f ? 0.0f : vis;
}

static void closest_n(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n,
                      enum RTCIntersectContextFlags flags)
{
    pane_log log;
    query_ctx ctx;
    query_init(&ctx, flags, PANE_DRAW, log.met, log.num_met);
    struct RTCRayHit rh[STREAM_CHUNK];
    for (size_t base = 0; base < n; base += STREAM_CHUNK) {
        unsigned m = (unsigned)((n - base) < STREAM_CHUNK ? (n - base) : STREAM_CHUNK);
        for (unsigned i = 0; i < m; i++) {
            to_rtc_ray(&rays[base + i], &rh[i].ray);
            rh[i].ray.id = i;
            rh[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        }
        if (t->has_panes)
            memset(log.num_met, 0, m * sizeof log.num_met[0]);
        rtcIntersect1M(t->scene, &ctx.rtc, rh, m, sizeof rh[0]);
        for (unsigned i = 0; i < m; i++)
            from_rtc_hit(&rh[i], &hits[base + i]);
    }
}

void il_trace_closest_n(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n)
{
    closest_n(t, rays, hits, n, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT);
}

void il_trace_closest_n_coherent(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n)
{
    closest_n(t, rays, hits, n, RTC_INTERSECT_CONTEXT_FLAG_COHERENT);
}

void il_trace_occluded_n(const il_tracer *t, const il_ray *rays, bool *occluded, size_t n)
{
    query_ctx ctx;
    query_init(&ctx, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, PANE_CLEAR, NULL, NULL);
    struct RTCRay r[STREAM_CHUNK];
    for (size_t base = 0; base < n; base += STREAM_CHUNK) {
        unsigned m = (unsigned)((n - base) < STREAM_CHUNK ? (n - base) : STREAM_CHUNK);
        for (unsigned i = 0; i < m; i++)
            to_rtc_ray(&rays[base + i], &r[i]);
        rtcOccluded1M(t->scene, &ctx.rtc, r, m, sizeof r[0]);
        for (unsigned i = 0; i < m; i++)
            occluded[base + i] = r[i].tfar < 0.0f;
    }
}

void il_trace_visibility_n(const il_tracer *t, const il_ray *rays, float *vis, size_t n)
{
    pane_log log;
    query_ctx ctx;
    query_init(&ctx, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, PANE_WEIGH, log.met, log.num_met);
    struct RTCRay r[STREAM_CHUNK];
    for (size_t base = 0; base < n; base += STREAM_CHUNK) {
        unsigned m = (unsigned)((n - base) < STREAM_CHUNK ? (n - base) : STREAM_CHUNK);
        ctx.vis = vis + base;
        for (unsigned i = 0; i < m; i++) {
            to_rtc_ray(&rays[base + i], &r[i]);
            r[i].id = i;
            vis[base + i] = 1.0f;
        }
        if (t->has_panes)
            memset(log.num_met, 0, m * sizeof log.num_met[0]);
        rtcOccluded1M(t->scene, &ctx.rtc, r, m, sizeof r[0]);
        for (unsigned i = 0; i < m; i++)
            if (r[i].tfar < 0.0f)
                vis[base + i] = 0.0f;
    }
}

float il_trace_epsilon(const il_tracer *t) { return t->epsilon; }

il_vec3 il_offset_origin(const il_tracer *t, il_vec3 p, il_vec3 ng, il_vec3 dir)
{
    il_vec3 n = ng;
    /* Grow the offset with the coordinates' magnitude: float spacing does. */
    float mag = il_maxf(fabsf(p.x), il_maxf(fabsf(p.y), fabsf(p.z)));
    float eps = t->epsilon + mag * 4.0f * FLT_EPSILON;
    return v3_dot(n, dir) >= 0.0f ? v3_fma(p, n, eps) : v3_fma(p, n, -eps);
}

il_ray il_shadow_ray(const il_tracer *t, il_vec3 p, il_vec3 ng, il_vec3 q, il_vec3 nq)
{
    il_vec3 d = v3_sub(q, p);
    il_vec3 o = il_offset_origin(t, p, ng, d);
    il_vec3 target = v3_is_zero(nq) ? q : il_offset_origin(t, q, nq, v3_neg(d));
    il_ray r;
    r.org = o;
    r.dir = v3_sub(target, o);
    r.tmin = 0.0f;
    r.tmax = 1.0f - 1e-4f;
    return r;
}
