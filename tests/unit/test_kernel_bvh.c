/* The shared kernel ray caster (src/kernel/kernel_bvh.h, compiled here by gcc
 * exactly as nvcc compiles it for the GPU) against Embree (trace/trace.h):
 * the same closest hits (triangle, t, barycentrics) and the same occlusion
 * answers on the Cornell box, the Stanford bunny and dragon, for random rays,
 * rays aimed at the surface and random segments; and the invariants of the
 * flattened BVH that bvh_build.c writes. */
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "core/rng.h"
#include "kernel/bvh_build.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* Analytic hits on one triangle: t, b1, b2 of Möller–Trumbore. */
static void test_triangle(void)
{
    ilk_tri tri;
    memset(&tri, 0, sizeof tri);
    tri.v0 = ilk_v3(0, 0, 0);
    tri.e1 = ilk_v3(2, 0, 0);
    tri.e2 = ilk_v3(0, 4, 0);
    float t, b1, b2;
    /* Point (0.5, 1, 0) = v0 + 0.25 e1 + 0.25 e2, from z = 3 straight down. */
    CHECK(ilk_intersect_tri(&tri, ilk_v3(0.5f, 1, 3), ilk_v3(0, 0, -1), 0, INFINITY, &t, &b1, &b2));
    CHECK_NEAR(t, 3, 1e-6);
    CHECK_NEAR(b1, 0.25, 1e-6);
    CHECK_NEAR(b2, 0.25, 1e-6);
    /* From below (back face) with an unnormalised direction: t in units of |dir|. */
    CHECK(ilk_intersect_tri(&tri, ilk_v3(0.5f, 1, -3), ilk_v3(0, 0, 2), 0, INFINITY, &t, &b1, &b2));
    CHECK_NEAR(t, 1.5, 1e-6);
    /* Outside the edge b1 + b2 = 1, beyond tmax, behind tmin, parallel. */
    CHECK(!ilk_intersect_tri(&tri, ilk_v3(1.5f, 2.5f, 3), ilk_v3(0, 0, -1), 0, INFINITY, &t, &b1, &b2));
    CHECK(!ilk_intersect_tri(&tri, ilk_v3(0.5f, 1, 3), ilk_v3(0, 0, -1), 0, 2.9f, &t, &b1, &b2));
    CHECK(!ilk_intersect_tri(&tri, ilk_v3(0.5f, 1, 3), ilk_v3(0, 0, 1), 0, INFINITY, &t, &b1, &b2));
    CHECK(!ilk_intersect_tri(&tri, ilk_v3(0.5f, 1, 3), ilk_v3(1, 0, 0), 0, INFINITY, &t, &b1, &b2));
    CHECK(sizeof(ilk_bvh_node) == 32);
    CHECK(sizeof(ilk_tri) == 48);
    CHECK(sizeof(ilk_ray) == sizeof(il_ray));
}

/* Every node reachable once, every triangle in exactly one leaf, children
 * inside their parent, leaves around their triangles, depth within the stack. */
static void check_invariants(const char *name, const il_scene *s, const il_kbvh *b)
{
    uint32_t n = b->num_tris;
    uint64_t total = 0;
    for (uint32_t m = 0; m < s->num_meshes; m++)
        total += s->meshes[m].num_triangles;
    CHECK(n == total);
    CHECK(b->num_nodes == 2 * b->num_leaves - 1);
    CHECK(b->depth < ILK_BVH_MAX_DEPTH);
    uint32_t *tri_seen = calloc(n, sizeof *tri_seen);
    uint32_t *node_seen = calloc(b->num_nodes, sizeof *node_seen);
    uint32_t *stack = malloc(sizeof *stack * (b->num_nodes + 1));
    /* (mesh, prim) pairs cover the scene once: count per mesh offset. */
    uint32_t *offset = calloc(s->num_meshes + 1, sizeof *offset);
    for (uint32_t m = 0; m < s->num_meshes; m++)
        offset[m + 1] = offset[m] + s->meshes[m].num_triangles;
    uint32_t *orig_seen = calloc(n, sizeof *orig_seen);
    int bad_child = 0, bad_leaf = 0, bad_ref = 0;
    uint32_t sp = 0, leaves = 0;
    stack[sp++] = 0;
    while (sp) {
        uint32_t i = stack[--sp];
        const ilk_bvh_node *nd = &b->nodes[i];
        node_seen[i]++;
        if (nd->count == 0) {
            for (int c = 0; c < 2; c++) {
                const ilk_bvh_node *ch = &b->nodes[nd->first + c];
                for (int a = 0; a < 3; a++)
                    if (ch->lo[a] < nd->lo[a] || ch->hi[a] > nd->hi[a] || ch->lo[a] > ch->hi[a])
                        bad_child++;
                stack[sp++] = nd->first + c;
            }
            continue;
        }
        leaves++;
        for (uint32_t t = nd->first; t < nd->first + nd->count && t < n; t++) {
            tri_seen[t]++;
            const ilk_tri *tr = &b->tris[t];
            if (tr->mesh >= s->num_meshes || tr->prim >= s->meshes[tr->mesh].num_triangles) {
                bad_ref++;
                continue;
            }
            orig_seen[offset[tr->mesh] + tr->prim]++;
            const il_mesh *mesh = &s->meshes[tr->mesh];
            for (int k = 0; k < 3; k++) {
                il_vec3 p = mesh->positions[mesh->indices[3 * tr->prim + k]];
                float q[3] = {p.x, p.y, p.z};
                for (int a = 0; a < 3; a++)
                    if (q[a] < nd->lo[a] || q[a] > nd->hi[a])
                        bad_leaf++;
            }
            il_vec3 p0 = mesh->positions[mesh->indices[3 * tr->prim]];
            if (tr->v0.x != p0.x || tr->v0.y != p0.y || tr->v0.z != p0.z)
                bad_leaf++;
        }
    }
    int once = 1;
    for (uint32_t t = 0; t < n; t++)
        if (tri_seen[t] != 1 || orig_seen[t] != 1)
            once = 0;
    for (uint32_t i = 0; i < b->num_nodes; i++)
        if (node_seen[i] != 1)
            once = 0;
    CHECK(once);
    CHECK(leaves == b->num_leaves);
    CHECK(bad_child == 0);
    CHECK(bad_leaf == 0);
    CHECK(bad_ref == 0);
    printf("%s: %u triangles, %u nodes, %u leaves, depth %u\n", name, n, b->num_nodes, b->num_leaves, b->depth);
    free(tri_seen); free(node_seen); free(stack); free(offset); free(orig_seen);
}

static float rnd(il_pcg32 *r) { return il_pcg32_float(r); }

static il_vec3 random_dir(il_pcg32 *r)
{
    /* Uniform on the sphere (pbrt-v4 section A.5.2). */
    float z = 1 - 2 * rnd(r), phi = 2 * IL_PI * rnd(r), s = sqrtf(il_maxf(0, 1 - z * z));
    return v3(s * cosf(phi), s * sinf(phi), z);
}

static il_vec3 random_in(il_pcg32 *r, il_vec3 lo, il_vec3 hi, float grow)
{
    il_vec3 c = v3_scale(v3_add(lo, hi), 0.5f), h = v3_scale(v3_sub(hi, lo), 0.5f * grow);
    return v3(c.x + (2 * rnd(r) - 1) * h.x, c.y + (2 * rnd(r) - 1) * h.y, c.z + (2 * rnd(r) - 1) * h.z);
}

static il_vec3 random_surface_point(il_pcg32 *r, const il_scene *s)
{
    const il_mesh *m;
    do m = &s->meshes[il_pcg32_next(r) % s->num_meshes]; while (m->num_triangles == 0);
    uint32_t p = il_pcg32_next(r) % m->num_triangles;
    float u = rnd(r), v = rnd(r);
    if (u + v > 1) { u = 1 - u; v = 1 - v; }
    il_vec3 a = m->positions[m->indices[3 * p]], b = m->positions[m->indices[3 * p + 1]];
    il_vec3 c = m->positions[m->indices[3 * p + 2]];
    return v3_add(a, v3_add(v3_scale(v3_sub(b, a), u), v3_scale(v3_sub(c, a), v)));
}

/* Distance in barycentric space from the triangle's border: small means the
 * ray grazes an edge, where two float implementations may pick either of two
 * neighbouring triangles (or a hit and a miss at a silhouette). */
static float edge_distance(float b1, float b2) { return il_minf(il_minf(b1, b2), 1 - b1 - b2); }

typedef struct stats {
    int rays, hits, same, well, tri_differs, hit_differs, bad, occ_rays, occ_differs, occ_true;
    double max_t_rel, max_p_rel, max_t_rel_all, max_b_all;
} stats;

/* Compares one closest-hit query.  Both sides compute in float with
 * Möller–Trumbore-like formulas, so their answers differ by rounding that
 * grows as eps |org - v0| / (|e| cos): the 1e-5 bounds apply to
 * well-conditioned hits (incidence cosine above 0.05, distance above 1e-3
 * of the scene's size); every other hit must still be the same triangle
 * within 2e-3 in t.  The barycentric error is measured where it matters, as
 * the distance between the two hit points on the triangle relative to the
 * size of the numbers that enter it: |db1 e1 + db2 e2| / max(t |dir|, |org - v0|). */
static void compare_closest(const il_tracer *em, const ilk_bvh *kb, const il_ray *ray, float extent, stats *st)
{
    il_hit eh;
    ilk_hit kh;
    bool e = il_trace_closest(em, ray, &eh);
    ilk_ray kr;
    memcpy(&kr, ray, sizeof kr);
    bool k = ilk_bvh_closest(kb, &kr, &kh);
    st->rays++;
    if (e != k) {
        /* Allowed only at an edge of the one that hit. */
        float ed = e ? edge_distance(eh.b1, eh.b2) : edge_distance(kh.b1, kh.b2);
        if (ed > 1e-4f) {
            st->bad++;
            fprintf(stderr, "%s hit only: t %.9g b %.6g %.6g (tmin %g tmax %g)\n", e ? "embree" : "kernel",
                    e ? eh.t : kh.t, e ? eh.b1 : kh.b1, e ? eh.b2 : kh.b2, ray->tmin, ray->tmax);
        }
        else
            st->hit_differs++;
        return;
    }
    if (!e)
        return;
    st->hits++;
    const ilk_tri *tr = &kb->tris[kh.tri];
    double rel = fabs((double)kh.t - eh.t) / fabs((double)eh.t);
    if (tr->mesh != eh.mesh || tr->prim != eh.prim) {
        /* Coincident triangles (the scanned meshes hold some), neighbours
         * at a shared edge (the distances agree), or a ray nearly in the
         * plane of the triangle that one side hit (incidence cosine below
         * 1e-3: the determinant is rounding noise). */
        float graze = fabsf(v3_dot(eh.ng, ray->dir)) / (v3_length(eh.ng) * v3_length(ray->dir));
        if (rel > 1e-5 && graze > 1e-3f && edge_distance(eh.b1, eh.b2) > 1e-4f && edge_distance(kh.b1, kh.b2) > 1e-4f) {
            st->bad++;
            fprintf(stderr, "other triangle: t %.9g vs %.9g (tmin %g)\n", kh.t, eh.t, ray->tmin);
        } else
            st->tri_differs++;
        return;
    }
    st->same++;
    double db1 = (double)kh.b1 - eh.b1, db2 = (double)kh.b2 - eh.b2;
    double dp[3] = {db1 * tr->e1.x + db2 * tr->e2.x, db1 * tr->e1.y + db2 * tr->e2.y, db1 * tr->e1.z + db2 * tr->e2.z};
    double dist = (double)eh.t * v3_length(ray->dir);
    il_vec3 so = v3_sub(ray->org, v3(tr->v0.x, tr->v0.y, tr->v0.z));
    double prel = sqrt(dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2]) / fmax(dist, v3_length(so));
    il_vec3 n = v3_cross(v3(tr->e1.x, tr->e1.y, tr->e1.z), v3(tr->e2.x, tr->e2.y, tr->e2.z));
    float cosang = fabsf(v3_dot(n, ray->dir)) / (v3_length(n) * v3_length(ray->dir));
    if (rel > st->max_t_rel_all) st->max_t_rel_all = rel;
    double db = fmax(fabs(db1), fabs(db2));
    if (db > st->max_b_all) st->max_b_all = db;
    if (cosang > 0.05f && dist > 1e-3 * extent) {
        st->well++;
        if (rel > st->max_t_rel) st->max_t_rel = rel;
        if (prel > st->max_p_rel) st->max_p_rel = prel;
    }
}

static void compare_scene(const char *name, il_scene *s, int nrays, int nocc)
{
    il_error err = {0};
    il_tracer *em = NULL;
    il_kbvh b;
    CHECK_OK(il_tracer_create(s, &em, &err), &err);
    CHECK_OK(il_kbvh_build_scene(s, &b, &err), &err);
    if (!em || !b.num_nodes) {
        il_tracer_release(em);
        return;
    }
    check_invariants(name, s, &b);
    ilk_bvh kb = il_kbvh_view(&b);
    il_vec3 lo = v3(b.nodes[0].lo[0], b.nodes[0].lo[1], b.nodes[0].lo[2]);
    il_vec3 hi = v3(b.nodes[0].hi[0], b.nodes[0].hi[1], b.nodes[0].hi[2]);
    float extent = v3_length(v3_sub(hi, lo));
    il_pcg32 rng = il_pcg32_seed(10, 42);
    stats st = {0};
    for (int i = 0; i < nrays; i++) {
        il_ray ray = {.tmin = 0, .tmax = INFINITY};
        switch (i % 3) {
        case 0: /* random origin in the (grown) bounds, random direction */
            ray.org = random_in(&rng, lo, hi, 1.5f);
            ray.dir = random_dir(&rng);
            break;
        case 1: /* aimed at a random surface point from outside, unnormalised */
            ray.org = random_in(&rng, lo, hi, 3.0f);
            ray.dir = v3_scale(v3_sub(random_surface_point(&rng, s), ray.org), 0.5f);
            break;
        default: /* from a surface point (tmin off the surface), limited tmax */
            ray.org = random_surface_point(&rng, s);
            ray.dir = random_dir(&rng);
            ray.tmin = 1e-4f * extent;
            ray.tmax = rnd(&rng) * extent;
            break;
        }
        compare_closest(em, &kb, &ray, extent, &st);
    }
    for (int i = 0; i < nocc; i++) {
        /* Shadow segments between two points, as NEE casts them. */
        il_vec3 a = (i & 1) ? random_surface_point(&rng, s) : random_in(&rng, lo, hi, 1.2f);
        il_vec3 c = random_in(&rng, lo, hi, 1.2f);
        il_ray ray = {.org = a, .dir = v3_sub(c, a), .tmin = (i & 1) ? 1e-4f : 0.0f, .tmax = 1.0f};
        ilk_ray kr;
        memcpy(&kr, &ray, sizeof kr);
        bool e = il_trace_occluded(em, &ray);
        bool k = ilk_bvh_occluded(&kb, &kr);
        st.occ_rays++;
        st.occ_true += e;
        if (e != k) {
            /* Check it is a grazing case: the closest hit must sit at an edge
             * or at an end of the segment. */
            ilk_hit kh;
            il_hit eh;
            bool graze = false;
            if (ilk_bvh_closest(&kb, &kr, &kh))
                graze = edge_distance(kh.b1, kh.b2) < 1e-4f || kh.t > 0.9999f || kh.t < kr.tmin * 1.01f;
            if (il_trace_closest(em, &ray, &eh))
                graze = graze || edge_distance(eh.b1, eh.b2) < 1e-4f || eh.t > 0.9999f || eh.t < ray.tmin * 1.01f;
            st.occ_differs += graze;
            st.bad += !graze;
        }
    }
    printf("%s: %d rays, %d hits: %d same triangle (%d well-conditioned: max rel dt %.3g, max rel dp %.3g; "
           "all: max rel dt %.3g, max dbary %.3g), %d coincident/edge neighbour, %d hit/miss at an edge, "
           "%d unexplained; %d segments, %d occluded, %d differ at a graze\n",
           name, st.rays, st.hits, st.same, st.well, st.max_t_rel, st.max_p_rel, st.max_t_rel_all, st.max_b_all,
           st.tri_differs, st.hit_differs, st.bad, st.occ_rays, st.occ_true, st.occ_differs);
    CHECK(st.hits > nrays / 4);
    CHECK(st.well > st.hits * 3 / 4);
    CHECK(st.max_t_rel <= 1e-5);
    CHECK(st.max_p_rel <= 1e-5);
    CHECK(st.max_t_rel_all <= 2e-3);
    CHECK(st.bad == 0);
    CHECK(st.tri_differs + st.hit_differs <= st.hits / 100);
    CHECK(st.occ_true > nocc / 10 && st.occ_true < nocc - nocc / 10);
    CHECK(st.occ_differs <= nocc / 1000);
    il_kbvh_free(&b);
    il_tracer_release(em);
}

static void test_scene(const char *name, const char *path, int nrays, int nocc)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_load(path, NULL, &s, &err), &err);
    if (s)
        compare_scene(name, s, nrays, nocc);
    il_scene_release(s);
}

/* An empty scene: an empty BVH that nothing hits. */
static void test_empty(void)
{
    il_error err = {0};
    il_scene *s = NULL;
    CHECK_OK(il_scene_create(&s, &err), &err);
    il_kbvh b;
    CHECK_OK(il_kbvh_build_scene(s, &b, &err), &err);
    CHECK(b.num_nodes == 0 && b.num_tris == 0);
    ilk_bvh kb = il_kbvh_view(&b);
    ilk_ray r;
    r.org = ilk_v3(0, 0, 0); r.dir = ilk_v3(0, 0, 1); r.tmin = 0; r.tmax = INFINITY;
    ilk_hit h;
    CHECK(!ilk_bvh_closest(&kb, &r, &h) && h.tri == UINT32_MAX);
    CHECK(!ilk_bvh_occluded(&kb, &r));
    il_kbvh_free(&b);
    il_scene_release(s);
}

int main(void)
{
    test_triangle();
    test_empty();
    test_scene("cornell", "cornell", 60000, 30000);
    test_scene("bunny", IL_SHARED_DIR "/scenes/stanford-bunny/bun_zipper.ply", 60000, 30000);
    test_scene("dragon", IL_SHARED_DIR "/scenes/stanford-dragon/dragon_vrip_res3.ply", 30000, 15000);
    return check_report();
}
