/* Hierarchical radiosity (`--method hr`): Hanrahan, Salzman & Aupperle,
 * "A Rapid Hierarchical Radiosity Algorithm", SIGGRAPH 1991, as in the
 * SPLASH-2 radiosity program.  Internals shared by the files of this folder
 * and the tests; see docs/hierarchical-radiosity.md.
 *
 * Pipeline (hr.c):
 *   scene -> il_patch_mesh_build with one patch per input polygon (the
 *            shared mesher, methods/patch_mesh.c): the quadtree roots
 *         -> hr_solve (hr_solve.c): initial links between facing roots
 *            (hr_link.c: form factor + visibility), then per iteration
 *            BF refinement (hr_refine.c), gather and push-pull
 *         -> hr_output_mesh (hr_output.c): the leaves as an il_patch_mesh by
 *            repeated il_patch_mesh_refine passes, their radiance per patch
 *         -> il_patch_vertex_radiance, il_patch_render_film or the bake.
 *
 * Quantities: radiance, as in radiosity (B = pi L for a Lambertian surface;
 * the equation B = E + rho sum F B holds unchanged for L).
 *
 * Determinism: every element has an id that is a pure function of its root
 * patch and its quadtree path; all random numbers are keyed by ids; an
 * element's children are a pure function of the element (created by
 * whichever thread gets there first, published with a compare-and-swap);
 * each element's links are refined by one task in a fixed order (its
 * parent's task hands links down, then its own task, started after that,
 * refines them) and gathered by one task.  So elements, links and
 * radiances do not depend on the thread count or timing. */
#ifndef IL_METHODS_HR_HR_H
#define IL_METHODS_HR_HR_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "core/sampling.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "methods/patch_mesh.h"
#include "scene/scene.h"

/* Most quadtree levels below a root (the area epsilon stops far earlier). */
#define IL_HR_MAX_LEVEL 24
#define IL_HR_MAX_VIS_RAYS 4096u
#define IL_HR_MAX_ITERATIONS 100000u

/* ------------------------------------------------------------- settings */

struct il_hr_solver;

typedef struct il_hr_settings {
    float bf_eps;
    float area_eps;            /* relative to the scene diagonal squared */
    float energy_eps;
    uint32_t vis_rays;
    uint32_t max_iterations;
    uint64_t seed;
    int threads;               /* > 0, resolved */
    /* The bytes the initial links may take: half the physical memory.  A
     * scene that needs more is refused before any link is made (hr_solve.c). */
    uint64_t link_memory_limit;
    const il_distrib *distrib; /* the render split across processes (hr_distrib.c); NULL: not */
    /* Internal (il_bake_progressive, bake.c): called after every iteration
     * (refine, gather, push-pull) with the solver; false stops the
     * iterations.  NULL from il_hr_settings_resolve. */
    bool (*on_iteration)(const struct il_hr_solver *solver, void *user);
    void *on_iteration_user;
    il_hr_step_fn on_step;     /* il_hr_desc.on_step (NULL when split across processes) */
    void *on_step_user;
} il_hr_settings;

/* Resolves defaults and checks ranges (clear messages, IL_ERR_INVALID). */
il_status il_hr_settings_resolve(const il_render_desc *desc, il_hr_settings *out, il_error *err);

/* ------------------------------------------------------- elements, links */

typedef struct il_hr_elem il_hr_elem;

/* A link: the receiver (the element whose list holds it) gathers from `src`. */
typedef struct il_hr_link {
    il_hr_elem *src;
    float ff;                  /* F_rs: form factor from the receiver to src */
    float err_ff;              /* the refinement oracle's form-factor bound; 0 when
                                  the link can never be split (both elements at
                                  the smallest size) */
    float vis;                 /* visible fraction in [0, 1] */
    float vis_bound;           /* the oracle's visibility: an upper bound of vis */
    struct il_hr_link *next;
} il_hr_link;

struct il_hr_elem {
    il_vec3 corners[4];        /* counter-clockwise from the front */
    il_vec3 center, normal;
    float area;
    uint32_t num_corners;      /* 3 or 4 */
    uint32_t root;             /* the patch (quadtree root) it lies in */
    uint32_t level;            /* 0 for a root */
    uint64_t id;               /* pure function of root and quadtree path */
    il_vec3 rho;               /* the root patch's reflectance */
    il_vec3 emit;              /* Le + rho/pi * direct irradiance (delta lights, sky) */
    il_vec3 radiance;          /* B: outgoing radiance (leaves), area mean (inner) */
    float exposure;            /* fraction of the area not buried in a solid (hr_exposure.c) */
    il_vec3 gathered;          /* H: sum over own links of F V B_src (not times rho) */
    il_vec3 incoming;          /* leaves: H pushed down from all ancestors and own */
    il_hr_link *links, *links_tail; /* as receiver; touched by the root's task only */
    uint32_t num_links;
    il_hr_elem *parent;
    _Atomic(il_hr_elem *) children; /* NULL or 4 elements, published by CAS */
};

/* Per-thread chunked arenas of elements and links: no malloc in the hot
 * loop but one per chunk, no lock; a link replaced by refinement goes to
 * the freeing thread's free list. */
typedef struct il_hr_chunk il_hr_chunk;
typedef struct il_hr_pool {
    il_hr_chunk *elem_chunks, *link_chunks;
    size_t elem_used, elem_cap;    /* in the newest element chunk */
    size_t link_used, link_cap;
    il_hr_link *free_links;
    uint64_t bytes;
    uint64_t elements;             /* counters (summed over threads: deterministic totals) */
    uint64_t links_made;
    uint64_t vis_rays;
    bool failed;                   /* out of memory */
    char pad[64];
} il_hr_pool;

void il_hr_pool_init(il_hr_pool *pool);
void il_hr_pool_free(il_hr_pool *pool);
/* Four contiguous elements, or NULL (pool->failed set). */
il_hr_elem *il_hr_pool_elems4(il_hr_pool *pool);
/* Gives back the block just taken by il_hr_pool_elems4 (a lost CAS). */
void il_hr_pool_unget4(il_hr_pool *pool);
il_hr_link *il_hr_pool_link(il_hr_pool *pool);
void il_hr_pool_put_link(il_hr_pool *pool, il_hr_link *link);

/* ---------------------------------------------------------- the solver */

typedef struct il_hr_solver {
    const il_scene *scene;
    const il_patch_mesh *mesh;      /* one patch per input polygon */
    il_hr_settings set;
    il_hr_elem *roots;              /* one per mesh patch */
    uint32_t num_roots;
    il_hr_pool *pools;              /* one per thread */
    float diag;                     /* scene bounding-box diagonal */
    float area_min;                 /* area_eps * diag^2 */
    float b_max;                    /* largest emitted luminance (0: nothing to solve) */
    float b_ref;                    /* mean emitted luminance sum A Le / sum A: the
                                       refinement's radiance scale (hr_refine.c) */
    float plane_eps;                /* distance below which a point is on a plane */
    bool delta_lights, sky;         /* direct light to add to the leaves' emission */
    uint32_t *order;                /* roots by decreasing work (scheduling only) */
    uint32_t *vis_strata;           /* il_hr_vis_strata: vis_rays entries */
    uint32_t vis_m;                 /* visibility strata per side */
    bool vis_pow2;                  /* vis_m a power of two (> 1), vis_rays = vis_m^2 */
    struct il_hr_link_table *table; /* split across processes: the links this
                                       refinement makes, computed by all (hr_distrib.c) */
    il_hr_stats stats;
    struct il_hr_watch *watch;      /* progress and the stop request (hr_progress.c) */
} il_hr_solver;

/* ------------------------------------------------------------ progress */

/* il_hr_desc.on_step's state during a solve: it is called from thread 0
 * alone (the caller's), so only `stop` and `roots_done` are shared. */
typedef struct il_hr_watch {
    atomic_bool stop;               /* on_step returned false */
    atomic_uint roots_done;         /* in the current phase */
    il_hr_phase phase;
    uint32_t iterations;
    uint32_t polls;                 /* il_hr_watch_poll calls on thread 0 */
    double t0, next_report;         /* omp_get_wtime seconds */
} il_hr_watch;

/* Starts watching: s->watch = w, phase LINKING. */
void il_hr_watch_start(il_hr_solver *s, il_hr_watch *w);
/* A new phase: roots_done back to 0; reports it at once. */
void il_hr_watch_phase(const il_hr_solver *s, il_hr_phase phase, uint32_t iterations,
                       double energy_change);
/* A root's links made or refined. */
void il_hr_watch_root_done(const il_hr_solver *s);
/* On thread 0, at most ten times a second: reports the phase's progress.
 * Cheap enough to call for every link. */
void il_hr_watch_poll(const il_hr_solver *s);
/* Whether on_step asked to stop. */
static inline bool il_hr_stopping(const il_hr_solver *s)
{
    return s->watch && atomic_load_explicit(&s->watch->stop, memory_order_relaxed);
}

/* Roots from the mesh, initial links, iterations (refine, gather, push-pull)
 * until the energy converges.  On failure the solver is freed. */
il_status il_hr_solve(const il_scene *scene, const il_patch_mesh *mesh, const il_hr_settings *set,
                      il_hr_solver *solver, il_error *err);
void il_hr_solver_free(il_hr_solver *solver);

/* The children of e (created when missing: race-free, the same whoever
 * creates them); NULL only when out of memory. */
il_hr_elem *il_hr_children(const il_hr_solver *s, il_hr_elem *e, il_hr_pool *pool);
static inline il_hr_elem *il_hr_children_get(const il_hr_elem *e)
{
    return atomic_load_explicit(&((il_hr_elem *)e)->children, memory_order_acquire);
}
/* Fills a root element from mesh patch i; returns the rays it cast. */
uint32_t il_hr_elem_root(const il_hr_solver *s, uint32_t i, il_hr_elem *out);
/* The point at (u, v) of the unit square mapped onto the element (bilinear
 * for quads, the area-preserving square-to-triangle map for triangles).
 * Inline: the visibility rays draw two per ray. */
static inline il_vec3 il_hr_elem_point(const il_hr_elem *e, float u, float v)
{
    const il_vec3 *c = e->corners;
    if (e->num_corners == 4)
        return v3_add(v3_add(v3_scale(c[0], (1 - u) * (1 - v)), v3_scale(c[1], u * (1 - v))),
                      v3_add(v3_scale(c[2], u * v), v3_scale(c[3], (1 - u) * v)));
    il_vec2 b = il_sample_triangle(v2(u, v));
    return v3_add(v3_add(v3_scale(c[0], 1.0f - b.x - b.y), v3_scale(c[1], b.x)),
                  v3_scale(c[2], b.y));
}

/* The fraction of e's area not buried inside a solid, by probe rays;
 * *rays_cast: how many it cast. */
float il_hr_exposure(const il_hr_solver *s, const il_hr_elem *e, uint32_t *rays_cast);
/* The mean radiance over e's exposed part: what links gather from e and
 * what the output shows (hr_exposure.c explains why). */
static inline il_vec3 il_hr_exposed_radiance(const il_hr_elem *e)
{
    return e->exposure > 0.0f ? v3_scale(e->radiance, 1.0f / e->exposure) : v3s(0.0f);
}

/* A new link (r gathers from src) with its form factor; its visibility is
 * left unknown (vis < 0) for il_hr_link_visibility, or 0 when F is 0.
 * NULL when out of memory. */
il_hr_link *il_hr_link_make(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                            il_hr_elem *src);

/* il_hr_link_make's computation into *l (no pool, no counter). */
void il_hr_link_fill(const il_hr_solver *s, const il_hr_elem *r, il_hr_elem *src, il_hr_link *l);

/* Whether the refinement splits link l (receiver r) when its visibility
 * bound is vis_bound (hr_refine.c explains the test). */
static inline bool il_hr_splits(const il_hr_solver *s, const il_hr_elem *r, const il_hr_link *l,
                                float vis_bound)
{
    if (!(vis_bound > 0.0f && l->err_ff > 0.0f))
        return false;
    float bf = l->err_ff * il_luminance(il_hr_exposed_radiance(l->src)) * vis_bound;
    if (!(bf > s->set.bf_eps * s->b_ref))
        return false;
    const il_hr_elem *big = r->area >= l->src->area ? r : l->src;
    return big->area > s->area_min && big->level < IL_HR_MAX_LEVEL;
}

/* Appends link l to the end of receiver r's list (the order refinement and
 * gathering read it in). */
static inline void il_hr_link_append(il_hr_elem *r, il_hr_link *l)
{
    l->next = NULL;
    if (r->links_tail)
        r->links_tail->next = l;
    else
        r->links = l;
    r->links_tail = l;
    r->num_links++;
}
/* Casts link l's visibility rays (r: its receiver).  parent_visible: the
 * link it replaces had every ray pass, so a few rays that all pass give
 * V = 1; split_if_visible: the refinement splits l as soon as any ray
 * passes, so the first one that passes ends it (hr_link.c). */
void il_hr_link_visibility(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                           il_hr_link *l, bool parent_visible, bool split_if_visible);
/* The unoccluded form factor from a differential area at p (normal n) to
 * the triangle or quad poly (hr_ff.c: methods/ff_analytic.c's formula with
 * a cheaper arctangent; they agree within 1e-8). */
double il_hr_ff_point_polygon(il_vec3 p, il_vec3 n, const il_vec3 *poly, uint32_t count);
/* The same from each of npts <= 4 points with normal n, out[i] for
 * pts[i] (several at once: vectorized when nothing needs clipping). */
void il_hr_ff_points_polygon(const il_vec3 *pts, uint32_t npts, il_vec3 n, const il_vec3 *poly,
                             uint32_t count, double *out);
/* The order in which a link's n visibility rays visit the strata of an
 * m x m grid (m = ceil(sqrt(n))): strata[k] = column | row << 16.  When n
 * is the square of a power of two (16 by default, *pow2 set) the order is
 * bit-reversed and interleaved (k's even bits reversed give the column,
 * its odd bits the row), so each run of 4 draws from a multiple of 4 covers
 * the four quadrants: the first 4 rays are a 2 x 2 stratified set of their
 * own; otherwise row by row. */
void il_hr_vis_strata(uint32_t n, uint32_t *m, bool *pow2, uint32_t *strata);
/* Whether a and b face each other: each has a point strictly in front of
 * the other's plane. */
bool il_hr_facing(const il_hr_solver *s, const il_hr_elem *a, const il_hr_elem *b);

/* BF refinement of every link received by e's subtree: e's own links,
 * then each child's subtree (in OpenMP tasks near the root, when called
 * inside a parallel region); the running thread's pool. */
void il_hr_refine_tree(const il_hr_solver *s, il_hr_elem *e);
/* Split across processes (hr_distrib.c): finds, sweep by sweep, every link
 * the coming refinement makes or whose visibility it needs, has each
 * process compute its contiguous share of each sweep's links, gathers them
 * in rank order and fills s->table, which il_hr_refine_tree then reads
 * instead of computing.  Every process calls it, outside any parallel
 * region, before each refinement; the table is kept for the next one. */
il_status il_hr_distrib_plan(il_hr_solver *s, il_error *err);
void il_hr_distrib_table_free(il_hr_solver *s);
#define IL_HR_NO_ENTRY UINT32_MAX
/* Table entry `at` into *l (its rays added to pool) when it is the link
 * r <- src made under a link whose rays all passed when parent_visible;
 * false otherwise (then the caller computes the link). */
bool il_hr_distrib_take(const il_hr_solver *s, il_hr_pool *pool, uint32_t at, const il_hr_elem *r,
                        il_hr_elem *src, bool parent_visible, il_hr_link *l);
/* The same for an existing link l of r whose visibility is unknown, found
 * by its address; *at: its entry. */
bool il_hr_distrib_take_old(const il_hr_solver *s, il_hr_pool *pool, const il_hr_elem *r,
                            il_hr_link *l, bool parent_visible, uint32_t *at);
/* The entry of the first link that replaces link l of r when it splits (l
 * taken from entry `at`, or IL_HR_NO_ENTRY: an existing link, found by
 * address); IL_HR_NO_ENTRY when the table has none. */
uint32_t il_hr_distrib_first_child(const il_hr_solver *s, const il_hr_elem *r,
                                   const il_hr_link *l, uint32_t at);

/* Gather (H = sum F V B) over root r's tree, then push-pull it: leaves get
 * radiance = emit + rho * (H pushed down), inner elements the area mean. */
void il_hr_gather_root(il_hr_elem *root);
void il_hr_push_pull_root(il_hr_elem *root);

/* --------------------------------------------------------------- output */

/* The leaves as a patch mesh (il_patch_mesh_refine passes on solver->mesh,
 * splitting where the quadtree did) and each of its patches' radiance. */
il_status il_hr_output_mesh(const il_hr_solver *s, il_patch_mesh **mesh_out,
                            il_vec3 **patch_radiance_out, il_error *err);

/* The quadtree roots: the scene meshed with one patch per input polygon
 * (quads stay quads). */
il_status il_hr_root_mesh(const il_scene *scene, il_patch_mesh **out, il_error *err);

/* The whole method: settings, roots, solve, output mesh, per-vertex
 * radiance.  The caller owns *mesh_out and *vertex_radiance_out (free());
 * stats->hr is filled. */
il_status il_hr_run(const il_scene *scene, const il_render_desc *desc, il_patch_mesh **mesh_out,
                    il_vec3 **vertex_radiance_out, il_render_stats *stats, il_error *err);
/* il_hr_run that hands the leaves' mesh and per-patch radiance (3 floats per
 * patch) to on_patches after every iteration; false stops the iterations. */
il_status il_hr_run_watched(const il_scene *scene, const il_render_desc *desc,
                            bool (*on_patches)(const il_patch_mesh *mesh, const float *radiance,
                                               void *user),
                            void *on_patches_user, il_patch_mesh **mesh_out,
                            il_vec3 **vertex_radiance_out, il_render_stats *stats, il_error *err);

/* The il_render entry point for IL_METHOD_HR. */
il_status il_hr_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_render_stats *stats, il_error *err);

#endif
