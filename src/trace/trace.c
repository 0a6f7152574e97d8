/* Embree 3 behind the il_tracer interface. */
#include "trace/trace.h"

#include <embree3/rtcore.h>
#include <float.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "scene/scene.h"

struct il_tracer {
    RTCDevice device;
    RTCScene scene;
    float epsilon;
    char embree_error[256];  /* first error Embree reported while building */
};

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
                             const uint32_t *indices, uint32_t num_triangles, uint32_t id)
{
    RTCGeometry g = rtcNewGeometry(t->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, positions, 0,
                               sizeof(il_vec3), num_vertices);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0,
                               3 * sizeof(uint32_t), num_triangles);
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
    for (uint32_t i = 0; i < scene->num_meshes; i++) {
        const il_mesh *m = &scene->meshes[i];
        attach_triangles(t, m->positions, m->num_vertices, m->indices, m->num_triangles, i);
    }
    return finish(t, out, err);
}

il_status il_tracer_create_triangles(const il_vec3 *positions, uint32_t num_vertices,
                                     const uint32_t *indices, uint32_t num_triangles,
                                     il_tracer **out, il_error *err)
{
    il_tracer *t;
    il_status st = begin(&t, err);
    if (st != IL_OK)
        return st;
    attach_triangles(t, positions, num_vertices, indices, num_triangles, 0);
    return finish(t, out, err);
}

void il_tracer_release(il_tracer *t)
{
    if (!t)
        return;
    if (t->scene)
        rtcReleaseScene(t->scene);
    if (t->device)
        rtcReleaseDevice(t->device);
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

bool il_trace_closest(const il_tracer *t, const il_ray *ray, il_hit *hit)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    to_rtc_ray(ray, &rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(t->scene, &ctx, &rh);
    return from_rtc_hit(&rh, hit);
}

bool il_trace_occluded(const il_tracer *t, const il_ray *ray)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay r;
    to_rtc_ray(ray, &r);
    rtcOccluded1(t->scene, &ctx, &r);
    return r.tfar < 0.0f; /* Embree sets tfar to -inf on a hit */
}

enum { STREAM_CHUNK = 256 };

static void closest_n(const il_tracer *t, const il_ray *rays, il_hit *hits, size_t n,
                      enum RTCIntersectContextFlags flags)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = flags;
    struct RTCRayHit rh[STREAM_CHUNK];
    for (size_t base = 0; base < n; base += STREAM_CHUNK) {
        unsigned m = (unsigned)((n - base) < STREAM_CHUNK ? (n - base) : STREAM_CHUNK);
        for (unsigned i = 0; i < m; i++) {
            to_rtc_ray(&rays[base + i], &rh[i].ray);
            rh[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rh[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect1M(t->scene, &ctx, rh, m, sizeof rh[0]);
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
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    struct RTCRay r[STREAM_CHUNK];
    for (size_t base = 0; base < n; base += STREAM_CHUNK) {
        unsigned m = (unsigned)((n - base) < STREAM_CHUNK ? (n - base) : STREAM_CHUNK);
        for (unsigned i = 0; i < m; i++)
            to_rtc_ray(&rays[base + i], &r[i]);
        rtcOccluded1M(t->scene, &ctx, r, m, sizeof r[0]);
        for (unsigned i = 0; i < m; i++)
            occluded[base + i] = r[i].tfar < 0.0f;
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
