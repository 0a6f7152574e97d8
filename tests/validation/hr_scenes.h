/* Helpers for the hierarchical radiosity validation tests: the solver run
 * step by step through hr.h, and sums over its leaves. */
#ifndef IL_TESTS_HR_SCENES_H
#define IL_TESTS_HR_SCENES_H

#include "mesh_compare.h"
#include "rad_scenes.h"
#include "methods/hr/hr.h"
#include "scene/camera.h"

typedef struct hr_case {
    il_patch_mesh *mesh;
    il_hr_solver solver;
} hr_case;

static inline il_status hr_case_run(const il_scene *s, const il_render_desc *rd, hr_case *c)
{
    memset(c, 0, sizeof *c);
    il_hr_settings set;
    il_status st = il_hr_settings_resolve(rd, &set, &g_err);
    if (st == IL_OK)
        st = il_hr_root_mesh(s, &c->mesh, &g_err);
    if (st == IL_OK)
        st = il_hr_solve(s, c->mesh, &set, &c->solver, &g_err);
    return st;
}

static inline void hr_case_free(hr_case *c)
{
    il_hr_solver_free(&c->solver);
    il_patch_mesh_release(c->mesh);
    memset(c, 0, sizeof *c);
}

/* Calls fn on every leaf of every quadtree, roots in order, children in order. */
typedef void (*hr_leaf_fn)(const il_hr_elem *leaf, void *user);
static inline void hr_visit_leaves(const il_hr_elem *e, hr_leaf_fn fn, void *user)
{
    const il_hr_elem *kids = il_hr_children_get(e);
    if (!kids) {
        fn(e, user);
        return;
    }
    for (int k = 0; k < 4; k++)
        hr_visit_leaves(&kids[k], fn, user);
}

static inline void hr_print_stats(const char *what, const il_hr_stats *h)
{
    printf("%s: %u patches, %llu elements, %llu leaves, %llu links, %u iterations, %llu rays, "
           "setup %.3f s, refine %.3f s, gather %.3f s, average %.3f s, %.1f MB\n",
           what, h->patches, (unsigned long long)h->elements, (unsigned long long)h->leaves,
           (unsigned long long)h->links, h->iterations, (unsigned long long)h->visibility_rays,
           h->seconds_setup, h->seconds_refine, h->seconds_gather, h->seconds_average,
           (double)h->peak_bytes / 1e6);
}

/* An axis-aligned box [lo, hi] of 6 outward-facing quads (a blocker). */
static inline void add_block(il_scene *s, il_vec3 lo, il_vec3 hi, uint32_t mat)
{
    il_vec3 c = v3_scale(v3_add(lo, hi), 0.5f), h = v3_scale(v3_sub(hi, lo), 0.5f);
    add_quad(s, v3(c.x, hi.y, c.z), v3(0, 0, h.z), v3(h.x, 0, 0), mat);  /* top, +y */
    add_quad(s, v3(c.x, lo.y, c.z), v3(h.x, 0, 0), v3(0, 0, h.z), mat);  /* bottom, -y */
    add_quad(s, v3(hi.x, c.y, c.z), v3(0, h.y, 0), v3(0, 0, h.z), mat);  /* +x */
    add_quad(s, v3(lo.x, c.y, c.z), v3(0, 0, h.z), v3(0, h.y, 0), mat);  /* -x */
    add_quad(s, v3(c.x, c.y, hi.z), v3(h.x, 0, 0), v3(0, h.y, 0), mat);  /* +z */
    add_quad(s, v3(c.x, c.y, lo.z), v3(0, h.y, 0), v3(h.x, 0, 0), mat);  /* -z */
}

/* A 1 m room (rad_scenes.h's coloured room) with a grey block that
 * shadows, standing on the floor or (`floating`) 0.1 m above it; `open`:
 * without its z=1 wall, so light escapes. */
static inline il_scene *hr_room(bool open, bool floating)
{
    il_scene *s = new_scene();
    uint32_t grey = diffuse_material(s, v3(0.7f, 0.7f, 0.7f), v3s(0));
    uint32_t red = diffuse_material(s, v3(0.75f, 0.15f, 0.1f), v3s(0));
    uint32_t green = diffuse_material(s, v3(0.1f, 0.6f, 0.15f), v3s(0));
    uint32_t lamp = diffuse_material(s, v3(0.5f, 0.5f, 0.5f), v3(8.0f, 7.5f, 6.5f));
    const float h = 0.5f;
    add_quad(s, v3(h, 0, h), v3(0, 0, h), v3(h, 0, 0), grey);
    add_quad(s, v3(h, 1, h), v3(h, 0, 0), v3(0, 0, h), grey);
    add_quad(s, v3(0, h, h), v3(0, h, 0), v3(0, 0, h), red);
    add_quad(s, v3(1, h, h), v3(0, 0, h), v3(0, h, 0), green);
    add_quad(s, v3(h, h, 0), v3(h, 0, 0), v3(0, h, 0), grey);
    if (!open)
        add_quad(s, v3(h, h, 1), v3(0, h, 0), v3(h, 0, 0), grey);
    add_quad(s, v3(0.5f, 0.98f, 0.5f), v3(0.15f, 0, 0), v3(0, 0, 0.15f), lamp);
    add_block(s, v3(0.3f, floating ? 0.1f : 0.0f, 0.35f), v3(0.6f, 0.4f, 0.6f), grey);
    set_camera(s, v3(0.5f, 0.5f, 0.98f), v3(0.5f, 0.45f, 0.0f), v3(0, 1, 0), 70.0f);
    return s;
}

#endif
