/* Ray casting through Embree: hits at known distances, occlusion, streams
 * equal single rays, and no self-intersection at millimetre or kilometre scale. */
#include "check.h"
#include "core/rng.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* A scene with one emissive quad in the plane z=0 (x,y in [-s,s]) and a
 * second quad at z=-2s, both facing +z. */
static il_scene *two_quads(float s)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    uint32_t lamp;
    CHECK_OK(il_scene_add_material(scene, &(il_material_desc){.emission = {1, 1, 1}}, &lamp, &err), &err);
    float p[] = {-s, -s, 0, s, -s, 0, s, s, 0, -s, s, 0,
                 -s, -s, -2 * s, s, -s, -2 * s, s, s, -2 * s, -s, s, -2 * s};
    uint32_t i0[] = {0, 1, 2, 0, 2, 3};
    uint32_t i1[] = {4, 5, 6, 4, 6, 7};
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.name = "front", .num_vertices = 8, .num_triangles = 2,
                                                       .positions = p, .indices = i0, .material = lamp}, &err), &err);
    CHECK_OK(il_scene_add_mesh(scene, &(il_mesh_desc){.name = "back", .num_vertices = 8, .num_triangles = 2,
                                                       .positions = p, .indices = i1}, &err), &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    return scene;
}

static void test_hits(float s)
{
    il_scene *scene = two_quads(s);
    const il_tracer *t = scene->tracer;
    il_hit hit;
    il_ray r = {.org = v3(0.1f * s, 0.2f * s, 5 * s), .dir = v3(0, 0, -1), .tmin = 0, .tmax = INFINITY};
    CHECK(il_trace_closest(t, &r, &hit));
    CHECK_REL(hit.t, 5 * s, 1e-5);
    CHECK(hit.mesh == 0);
    CHECK(il_trace_occluded(t, &r));
    r.tmax = 4.9f * s;
    CHECK(!il_trace_closest(t, &r, &hit));
    CHECK(!il_trace_occluded(t, &r));
    CHECK(hit.mesh == IL_HIT_NONE);

    /* A ray leaving the front quad towards -z hits the back quad, not itself;
     * one leaving towards +z hits nothing. */
    il_pcg32 rng = il_pcg32_seed(3, 4);
    int self_hits = 0, back_misses = 0;
    for (int i = 0; i < 2000; i++) {
        /* Start within 0.6s of the centre and tilt at most 0.15: the ray
         * lands within 0.9s on the back quad. */
        il_vec3 p = v3((2 * il_pcg32_float(&rng) - 1) * 0.6f * s, (2 * il_pcg32_float(&rng) - 1) * 0.6f * s, 0);
        il_vec3 d = v3_normalize(v3(0.3f * (il_pcg32_float(&rng) - 0.5f), 0.3f * (il_pcg32_float(&rng) - 0.5f), -1));
        il_ray down = {.org = il_offset_origin(t, p, v3(0, 0, 1), d), .dir = d, .tmin = 0, .tmax = INFINITY};
        if (!il_trace_closest(t, &down, &hit) || hit.mesh != 1)
            back_misses++;
        il_vec3 u = v3_neg(d);
        il_ray up = {.org = il_offset_origin(t, p, v3(0, 0, 1), u), .dir = u, .tmin = 0, .tmax = INFINITY};
        if (il_trace_closest(t, &up, &hit))
            self_hits++;
    }
    CHECK(self_hits == 0);
    CHECK(back_misses == 0);

    /* Shadow rays between the two quads: unoccluded (both ends lifted off). */
    int blocked = 0;
    for (int i = 0; i < 500; i++) {
        il_vec3 a = v3((2 * il_pcg32_float(&rng) - 1) * 0.9f * s, (2 * il_pcg32_float(&rng) - 1) * 0.9f * s, 0);
        il_vec3 b = v3((2 * il_pcg32_float(&rng) - 1) * 0.9f * s, (2 * il_pcg32_float(&rng) - 1) * 0.9f * s, -2 * s);
        il_ray sr = il_shadow_ray(t, a, v3(0, 0, 1), b, v3(0, 0, 1));
        blocked += il_trace_occluded(t, &sr);
    }
    CHECK(blocked == 0);

    /* Streams give the same answers as single rays. */
    enum { N = 1000 };
    il_ray rays[N];
    il_hit hits[N];
    bool occ[N];
    for (int i = 0; i < N; i++) {
        rays[i].org = v3((2 * il_pcg32_float(&rng) - 1) * 2 * s, (2 * il_pcg32_float(&rng) - 1) * 2 * s, 3 * s);
        rays[i].dir = v3(0.2f * (il_pcg32_float(&rng) - 0.5f), 0.2f * (il_pcg32_float(&rng) - 0.5f), -1);
        rays[i].tmin = 0;
        rays[i].tmax = i % 3 == 0 ? 4 * s : INFINITY;
    }
    il_trace_closest_n(t, rays, hits, N);
    il_trace_occluded_n(t, rays, occ, N);
    int mismatches = 0;
    for (int i = 0; i < N; i++) {
        il_hit h1;
        bool any = il_trace_closest(t, &rays[i], &h1);
        if (any != (hits[i].mesh != IL_HIT_NONE) || any != occ[i] || any != il_trace_occluded(t, &rays[i]))
            mismatches++;
        else if (any && (h1.mesh != hits[i].mesh || h1.prim != hits[i].prim || h1.t != hits[i].t))
            mismatches++;
    }
    CHECK(mismatches == 0);
    il_scene_release(scene);
}

int main(void)
{
    test_hits(1.0f);
    test_hits(1e-3f);  /* millimetre-sized scene */
    test_hits(1e3f);   /* kilometre-sized scene */
    return check_report();
}
