/* Quadtree elements (hr.h): roots from the patch mesh, children by a
 * midpoint split in exactly the order and shape of il_patch_mesh_refine
 * (methods/patch_mesh.c, split_patch), so the leaves can be turned back into
 * a patch mesh (hr_output.c).
 *
 * Children are created lazily by whichever task needs them first (a
 * receiver-side split by the root's own task, a source-side split by any
 * task): the task fills 4 elements from its own pool, and publishes them
 * with a compare-and-swap on the parent's `children`; a loser gives its
 * block back and uses the winner's.  The content is a pure function of the
 * parent (geometry, id, reflectance, emission with direct light keyed by
 * the id, and the parent's current radiance, which no task changes during
 * refinement), so the winner does not matter. */
#include <string.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "methods/hr/hr.h"
#include "methods/patch_direct.h"

static il_vec3 mid(il_vec3 a, il_vec3 b) { return v3_scale(v3_add(a, b), 0.5f); }

/* Area and centroid of a planar triangle or convex quad (the quad as two
 * triangles 0-1-2 and 0-2-3, as the patch builder does). */
static void shape(il_hr_elem *e)
{
    const il_vec3 *c = e->corners;
    if (e->num_corners == 3) {
        e->area = 0.5f * v3_length(v3_cross(v3_sub(c[1], c[0]), v3_sub(c[2], c[0])));
        e->center = v3_scale(v3_add(v3_add(c[0], c[1]), c[2]), 1.0f / 3.0f);
        return;
    }
    float a1 = 0.5f * v3_length(v3_cross(v3_sub(c[1], c[0]), v3_sub(c[2], c[0])));
    float a2 = 0.5f * v3_length(v3_cross(v3_sub(c[2], c[0]), v3_sub(c[3], c[0])));
    e->area = a1 + a2;
    il_vec3 g1 = v3_scale(v3_add(v3_add(c[0], c[1]), c[2]), 1.0f / 3.0f);
    il_vec3 g2 = v3_scale(v3_add(v3_add(c[0], c[2]), c[3]), 1.0f / 3.0f);
    e->center = e->area > 0.0f ? v3_scale(v3_add(v3_scale(g1, a1), v3_scale(g2, a2)), 1.0f / e->area)
                               : g1;
}

/* Le of the root patch plus rho/pi times the direct irradiance from delta
 * lights and the sky over this element (methods/patch_direct.c). */
static il_vec3 emission(const il_hr_solver *s, const il_hr_elem *e)
{
    il_vec3 le = s->mesh->patches[e->root].emission;
    if ((s->delta_lights || s->sky) && !v3_is_zero(e->rho)) {
        il_vec3 irr = il_patch_direct_irradiance(s->scene, e->corners, e->num_corners, e->normal,
                                                 s->set.seed, e->id, s->delta_lights, s->sky);
        le = v3_add(le, v3_scale(v3_mul(e->rho, irr), IL_INV_PI));
    }
    return le;
}

/* Emitters count as fully exposed: their emission is per unit of their
 * whole area, and a lamp half inside a solid is a modelling oddity. */
static uint32_t set_exposure(const il_hr_solver *s, const il_hr_elem *parent, il_hr_elem *e)
{
    uint32_t rays = 0;
    bool emitter = !v3_is_zero(s->mesh->patches[e->root].emission);
    e->exposure = emitter || (parent && parent->exposure >= 1.0f) ? 1.0f : il_hr_exposure(s, e, &rays);
    return rays;
}

uint32_t il_hr_elem_root(const il_hr_solver *s, uint32_t i, il_hr_elem *out)
{
    const il_patch *p = &s->mesh->patches[i];
    memset(out, 0, sizeof *out);
    out->num_corners = p->num_corners;
    for (uint32_t k = 0; k < p->num_corners; k++)
        out->corners[k] = s->mesh->positions[p->v[k]];
    shape(out);
    out->area = p->area; /* the builder's (double precision) value */
    out->normal = p->normal;
    out->root = i;
    out->id = il_hash64((uint64_t)i + 1u);
    out->rho = p->rho;
    out->emit = emission(s, out);
    out->radiance = out->emit;
    atomic_init(&out->children, NULL);
    return set_exposure(s, NULL, out);
}

/* Returns the rays it cast. */
static uint32_t fill_child(const il_hr_solver *s, const il_hr_elem *parent, uint32_t k,
                           const il_vec3 *corners, il_hr_elem *c)
{
    memset(c, 0, sizeof *c);
    c->num_corners = parent->num_corners;
    memcpy(c->corners, corners, parent->num_corners * sizeof *corners);
    shape(c);
    c->normal = parent->normal;
    c->root = parent->root;
    c->level = parent->level + 1;
    c->id = il_hash_combine(parent->id, (uint64_t)k + 1u);
    c->rho = parent->rho;
    c->emit = emission(s, c);
    /* Until the next push-pull: the parent's light, with the child's own
     * emission where the parent's differs (direct light varies). */
    c->radiance = v3_add(c->emit, v3_sub(parent->radiance, parent->emit));
    c->incoming = parent->incoming;
    c->parent = (il_hr_elem *)parent;
    atomic_init(&c->children, NULL);
    return set_exposure(s, parent, c);
}

il_hr_elem *il_hr_children(const il_hr_solver *s, il_hr_elem *e, il_hr_pool *pool)
{
    il_hr_elem *kids = il_hr_children_get(e);
    if (kids)
        return kids;
    il_hr_elem *block = il_hr_pool_elems4(pool);
    if (!block)
        return NULL;
    const il_vec3 *v = e->corners;
    uint32_t rays = 0;
    if (e->num_corners == 3) {
        il_vec3 m0 = mid(v[0], v[1]), m1 = mid(v[1], v[2]), m2 = mid(v[2], v[0]);
        const il_vec3 q[4][3] = {{v[0], m0, m2}, {m0, v[1], m1}, {m2, m1, v[2]}, {m0, m1, m2}};
        for (uint32_t k = 0; k < 4; k++)
            rays += fill_child(s, e, k, q[k], &block[k]);
    } else {
        il_vec3 m0 = mid(v[0], v[1]), m1 = mid(v[1], v[2]), m2 = mid(v[2], v[3]),
                m3 = mid(v[3], v[0]);
        il_vec3 c = v3_scale(v3_add(v3_add(v[0], v[1]), v3_add(v[2], v[3])), 0.25f);
        const il_vec3 q[4][4] = {
            {v[0], m0, c, m3}, {m0, v[1], m1, c}, {c, m1, v[2], m2}, {m3, c, m2, v[3]}};
        for (uint32_t k = 0; k < 4; k++)
            rays += fill_child(s, e, k, q[k], &block[k]);
    }
    il_hr_elem *expected = NULL;
    if (atomic_compare_exchange_strong_explicit(&e->children, &expected, block,
                                                memory_order_acq_rel, memory_order_acquire)) {
        pool->elements += 4;
        pool->vis_rays += rays; /* counted by the winner only: deterministic totals */
        return block;
    }
    il_hr_pool_unget4(pool); /* another task won: its children are the same */
    return expected;
}
