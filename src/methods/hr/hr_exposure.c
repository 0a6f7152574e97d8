/* Exposure of an element (hr.h): the fraction of its area that is not
 * buried inside a solid, such as the floor under a box standing on it.
 *
 * Why: a link carries F V B_s, with B_s the source's mean radiance and V the
 * fraction of rays between the two elements that pass.  Where part of the
 * source is buried, that part is dark (B = 0) and hidden (V = 0) at once, so
 * the product counts its darkness twice: a wall gathering from the whole
 * Cornell-box floor, 18% of which lies under the blocks, got 18% too little.
 * The transfer integral over the source, int B G V dy, only runs over its
 * exposed part E, where B is B_s / exposure on average, and F V already
 * estimates int_E G V dy; so links gather the exposed radiance
 * B_s / exposure (il_hr_exposed_radiance), and the output shows it too: the
 * camera only ever sees the exposed part of an element.
 *
 * A point is buried when every one of PROBE_RAYS cosine-distributed rays
 * from it reaches the back of a surface first (the inside of a solid); a
 * ray that escapes or meets a front face (a table top above a floor, seen
 * from below) proves it open, so a one-sided sheet above a surface does
 * not bury it.  exposure = open points / PROBE_POINTS (jittered strata
 * keyed by the element's id: deterministic).  A child of a fully exposed
 * element is taken as fully exposed without rays (a buried spot smaller
 * than the parent's strata can be missed: a small bias the other way). */
#include "core/rng.h"
#include "core/sampling.h"
#include "methods/hr/hr.h"

#define PROBE_GRID 4                              /* points: PROBE_GRID^2 */
#define PROBE_RAYS 4                              /* rays per point */
#define PROBE_POINTS (PROBE_GRID * PROBE_GRID)

/* Whether the triangle hit by a ray along dir is seen from its back. */
static bool back_face(const il_patch_mesh *m, uint32_t tri, il_vec3 dir)
{
    const uint32_t *t = m->tri_indices + 3 * (size_t)tri;
    il_vec3 p0 = m->positions[t[0]];
    il_vec3 ng = v3_cross(v3_sub(m->positions[t[1]], p0), v3_sub(m->positions[t[2]], p0));
    return v3_dot(ng, dir) > 0.0f;
}

float il_hr_exposure(const il_hr_solver *s, const il_hr_elem *e, uint32_t *rays_cast)
{
    const il_patch_mesh *m = s->mesh;
    il_pcg32 rng = il_pcg32_seed(il_hash_combine(s->set.seed, e->id), 0x6578706fu);
    il_frame f = il_frame_from_normal(e->normal);
    il_ray rays[PROBE_POINTS * PROBE_RAYS];
    il_hit hits[PROBE_POINTS * PROBE_RAYS];
    for (uint32_t k = 0; k < PROBE_POINTS; k++) {
        float u = ((float)(k % PROBE_GRID) + il_pcg32_float(&rng)) / PROBE_GRID;
        float v = ((float)(k / PROBE_GRID) + il_pcg32_float(&rng)) / PROBE_GRID;
        il_vec3 p = il_hr_elem_point(e, u, v);
        for (uint32_t j = 0; j < PROBE_RAYS; j++) {
            /* Directions stratified in 2 x 2 cells of the square. */
            float a = ((float)(j % 2) + il_pcg32_float(&rng)) * 0.5f;
            float b = ((float)(j / 2) + il_pcg32_float(&rng)) * 0.5f;
            il_vec3 d = il_frame_to_world(&f, il_sample_cosine_hemisphere(v2(a, b)));
            rays[k * PROBE_RAYS + j] = (il_ray){.org = il_offset_origin(m->tracer, p, e->normal, d),
                                                .tmin = 0.0f, .dir = d, .tmax = INFINITY};
        }
    }
    il_trace_closest_n(m->tracer, rays, hits, PROBE_POINTS * PROBE_RAYS);
    *rays_cast = PROBE_POINTS * PROBE_RAYS;
    uint32_t open = 0;
    for (uint32_t k = 0; k < PROBE_POINTS; k++) {
        bool buried = true;
        for (uint32_t j = 0; j < PROBE_RAYS && buried; j++) {
            const il_hit *h = &hits[k * PROBE_RAYS + j];
            buried = h->mesh != IL_HIT_NONE && back_face(m, h->prim, rays[k * PROBE_RAYS + j].dir);
        }
        open += !buried;
    }
    return (float)open / PROBE_POINTS;
}
