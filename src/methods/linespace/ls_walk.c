/* The injection's voxel walk (Amanatides & Woo 1987 in spirit: cell by
 * cell along the segment), see il_ls_walk in ls.h.  In a voxel with
 * triangles the segment's shaft is located by il_ls_find (the lookups'
 * SSE path, the same answers as il_ls_cell_of, il_ls_cell_box,
 * il_ls_locate and il_ls_shaft_index in turn); of an empty voxel, which
 * il_ls_find turns down, the walk needs only the exit (cell_exit).
 * tests/unit/test_ls_lookup.c holds it to the walk through that plain
 * chain, bit for bit. */
#include <math.h>

#include "methods/linespace/ls.h"

/* Where the line p + t d leaves the cell with corner lo: il_ls_locate's
 * t_out by the same operations (so the walk steps exactly as it would
 * with it), without the faces and patches an empty cell does not need. */
static inline float cell_exit(il_vec3 lo, il_vec3 size, il_vec3 p, il_vec3 d)
{
    float tf = INFINITY;
    for (int i = 0; i < 3; i++) {
        float di = v3_get(d, i);
        if (di == 0.0f) /* parallel to the slab: it never bounds the line */
            continue;
        float inv = 1.0f / di, l = v3_get(lo, i), h = l + v3_get(size, i), pi = v3_get(p, i);
        float far = di > 0.0f ? (h - pi) * inv : (l - pi) * inv;
        tf = far < tf ? far : tf;
    }
    return tf;
}

/* Whether a segment that starts inside a cell, -t_cell before the point
 * where its line (in shaft `shaft`, direction `dir`) enters the cell,
 * starts within tol of that entry face: its distance to the face's plane
 * is -t_cell times d's component across it. */
static bool starts_on_entry_face(const il_linespace *ls, il_vec3 d, uint32_t shaft, uint32_t dir, float t_cell,
                                 float tol)
{
    uint32_t fa, pa, fb, pb;
    il_ls_shaft_patches(ls->n, shaft, &fa, &pa, &fb, &pb);
    uint32_t entry = dir ? fb : fa; /* dir 0: from the lower face to the higher */
    return -t_cell * fabsf(v3_get(d, (int)(entry / 2u))) <= tol;
}

void il_ls_walk(const il_linespace *ls, il_vec3 o, il_vec3 d, float t_end, float start_tol,
                il_ls_visit visit, void *user)
{
    /* Clip to the grid box (slab method). */
    float t0 = 0.0f, t1 = t_end;
    for (int i = 0; i < 3; i++) {
        float di = v3_get(d, i), oi = v3_get(o, i);
        float lo = v3_get(ls->lo, i), hi = v3_get(ls->hi, i);
        if (di == 0.0f) {
            if (oi < lo || oi > hi)
                return;
            continue;
        }
        float a = (lo - oi) / di, b = (hi - oi) / di;
        if (a > b) {
            float tmp = a;
            a = b;
            b = tmp;
        }
        t0 = il_maxf(t0, a);
        t1 = il_minf(t1, b);
    }
    if (!(t1 > t0))
        return;
    const float step_eps = 1e-5f * v3_max_comp(ls->vsize);
    const float face_tol = 1e-4f * v3_max_comp(ls->vsize) + start_tol;
    float t = t0;
    for (int guard = 0; t < t1 && guard < 100000; guard++) {
        /* The cell the segment is in just after t. */
        il_vec3 p = v3_fma(o, d, il_minf(t + step_eps, 0.5f * (t + t1)));
        uint32_t voxel, shaft, dir;
        float tin, tout;
        bool located = il_ls_find(ls, p, d, &voxel, &shaft, &dir, &tin, &tout);
        if (!located) {
            uint32_t cc[3];
            if (!il_ls_cell_of(ls, p, cc))
                return;
            il_vec3 lo;
            il_ls_cell_box(ls, cc, &lo);
            tout = cell_exit(lo, ls->vsize, p, d);
        }
        float t_next = il_minf(t1, v3_dot(v3_sub(p, o), d) + tout);
        if (!(t_next > t))
            t_next = t + step_eps;
        if (located) {
            /* Where the line enters the cell, on the segment's parameter:
             * past its start for every cell but (mostly) the first. */
            float t_cell = v3_dot(v3_sub(p, o), d) + tin;
            bool entered = t_cell >= -step_eps || starts_on_entry_face(ls, d, shaft, dir, t_cell, face_tol);
            visit(user, voxel, shaft, dir, tout - tin, entered);
        }
        t = t_next;
    }
}

