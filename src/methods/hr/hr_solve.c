/* The hierarchical radiosity solve (hr.h): roots, initial links, then
 * iterations of a refinement followed by sweeps of gather and push-pull,
 * until what is left of the reflected energy sum(A lum(B - Le)) falls
 * below energy_eps of it (see energy_left).  An iteration sweeps until the
 * system on its links is solved to that test (at most IL_HR_MAX_SWEEPS
 * sweeps): a sweep costs little beside a refinement, and one sweep per
 * refinement, SPLASH-2's order, took about ln(eps) / ln(rho) refinements in
 * a room of albedo rho (48 at 0.95).  Gathering is Jacobi-style: every
 * element gathers from
 * the radiances of the previous push-pull, so the order of tasks does not
 * matter.
 *
 * Parallelism (work stealing by the OpenMP runtime, biggest trees first):
 * initial links (form factors only) in a dynamic loop over receiver roots;
 * refinement, with its visibility rays, in one task per root that hands the
 * subtrees of the top quadtree levels to tasks of their own
 * (il_hr_refine_tree); gather and push-pull in dynamic loops over roots.
 * No lock: per-thread pools, children published by CAS, each link list
 * built by one task at a time in a fixed order. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/hr/hr.h"
#include "methods/patch_direct.h"
#include "methods/radiosity/rad_stall.h"

/* What is left of the energy, from its last two changes d1 then d2.  The
 * iterations approach the solution geometrically, E_inf - E_k = d2 q / (1 -
 * q) with q = d2 / d1 (the reflectance the light sees), which exceeds the
 * last change itself once q > 1/2: SPLASH-2's test, the last change below
 * energy_eps, stopped a closed box of albedo 0.95 8.1% low
 * (test_hr_furnace) and left a white room's image 5.5% dark.  So the larger
 * of the two; a change that did not shrink leaves an unknown amount
 * (infinity). */
static double energy_left(double d1, double d2)
{
    if (d2 <= 0.0)
        return 0.0;
    if (!(d2 < d1))
        return INFINITY;
    double q = d2 / d1;
    return fmax(d2, d2 * q / (1.0 - q));
}

/* At most this many gather + push-pull sweeps per iteration. */
#define IL_HR_MAX_SWEEPS 64u

static void count_tree(const il_hr_elem *e, uint64_t *elems, uint64_t *leaves, uint64_t *links)
{
    (*elems)++;
    *links += e->num_links;
    const il_hr_elem *kids = il_hr_children_get(e);
    if (!kids) {
        (*leaves)++;
        return;
    }
    for (uint32_t k = 0; k < 4; k++)
        count_tree(&kids[k], elems, leaves, links);
}

/* The reflected energy sum(A lum(rho H)) (H area-averaged by the pull):
 * the total energy less the emission, which is constant and, when a small
 * bright lamp dominates the total, would hide the change of the indirect
 * light and stop the iteration too early. */
static double total_energy(const il_hr_solver *s)
{
    double e = 0.0;
    for (uint32_t i = 0; i < s->num_roots; i++) {
        const il_hr_elem *r = &s->roots[i];
        e += (double)r->area * il_luminance(v3_mul(r->rho, r->incoming));
    }
    return e;
}

static bool pools_failed(const il_hr_solver *s)
{
    for (int t = 0; t < s->set.threads; t++)
        if (s->pools[t].failed)
            return true;
    return false;
}

/* Scheduling order: roots with the most links first (only speed depends on it). */
typedef struct root_work { uint64_t links; uint32_t root; } root_work;

static int by_work(const void *a, const void *b)
{
    const root_work *x = a, *y = b;
    if (x->links != y->links)
        return x->links > y->links ? -1 : 1;
    return x->root < y->root ? -1 : (x->root > y->root);
}

static il_status reorder(il_hr_solver *s, il_error *err)
{
    root_work *w = il_malloc((size_t)s->num_roots * sizeof *w, err);
    if (!w)
        return IL_ERR_MEMORY;
    for (uint32_t i = 0; i < s->num_roots; i++) {
        uint64_t ne = 0, nl = 0, links = 0;
        count_tree(&s->roots[i], &ne, &nl, &links);
        w[i] = (root_work){links, i};
    }
    qsort(w, s->num_roots, sizeof *w, by_work);
    for (uint32_t i = 0; i < s->num_roots; i++)
        s->order[i] = w[i].root;
    free(w);
    return IL_OK;
}

void il_hr_solver_free(il_hr_solver *s)
{
    if (!s)
        return;
    if (s->pools)
        for (int t = 0; t < s->set.threads; t++)
            il_hr_pool_free(&s->pools[t]);
    free(s->pools);
    free(s->roots);
    free(s->order);
    free(s->vis_strata);
    il_hr_distrib_table_free(s);
    memset(s, 0, sizeof *s);
}

/* A root that reflects light gathers it through links (when any light is). */
static bool gathers(const il_hr_solver *s, const il_hr_elem *r)
{
    return !v3_is_zero(r->rho) && s->b_max > 0.0f;
}

/* How many roots root i links to initially: those facing it, when it
 * gathers. */
static uint64_t facing_row(const il_hr_solver *s, uint32_t i)
{
    if (!gathers(s, &s->roots[i]))
        return 0;
    uint64_t row = 0;
    for (uint32_t j = 0; j < s->num_roots; j++)
        row += j != i && il_hr_facing(s, &s->roots[i], &s->roots[j]);
    return row;
}

static il_status setup(il_hr_solver *s, il_error *err)
{
    uint32_t n = s->num_roots;
    int nt = s->set.threads;
    s->roots = il_malloc((size_t)(n ? n : 1u) * sizeof *s->roots, err);
    s->order = il_malloc((size_t)(n ? n : 1u) * sizeof *s->order, err);
    s->pools = il_calloc((size_t)nt, sizeof *s->pools, err);
    s->vis_strata = il_malloc((size_t)s->set.vis_rays * sizeof *s->vis_strata, err);
    if (!s->roots || !s->order || !s->pools || !s->vis_strata)
        return IL_ERR_MEMORY;
    il_hr_vis_strata(s->set.vis_rays, &s->vis_m, &s->vis_pow2, s->vis_strata);
    for (int t = 0; t < nt; t++)
        il_hr_pool_init(&s->pools[t]);
    uint64_t rays = 0;
#pragma omp parallel for schedule(dynamic, 16) num_threads(nt) reduction(+ : rays)
    for (uint32_t i = 0; i < n; i++)
        rays += il_hr_elem_root(s, i, &s->roots[i]);
    s->pools[0].vis_rays += rays;
    s->b_max = 0.0f;
    double power = 0.0, area = 0.0;
    for (uint32_t i = 0; i < n; i++) {
        s->order[i] = i;
        s->b_max = il_maxf(s->b_max, il_luminance(s->roots[i].emit));
        power += (double)s->roots[i].area * il_luminance(s->roots[i].emit);
        area += s->roots[i].area;
    }
    /* The refinement's scale: the mean emitted radiance.  Scaled by the
     * brightest emitter instead, a small bright lamp made every link
     * between lit surfaces look negligible and the solution 5-10% dark. */
    s->b_ref = area > 0.0 ? (float)(power / area) : 0.0f;
    /* Initial links: every pair of roots that face each other (a receiver
     * that reflects nothing needs none).  Their number grows with the square
     * of the patch count (Hanrahan et al. 1991 link the input polygons, with
     * no clustering), so it is held to a limit (half the physical memory): a
     * scene whose links would not fit is refused with a message instead of
     * the system killing the process part-way. */
    double link_bytes = (double)sizeof(il_hr_link), limit = (double)s->set.link_memory_limit;
    uint64_t max_links = (uint64_t)(limit / link_bytes), estimate = 0;
    bool limited = (double)n * (double)n * link_bytes > limit; /* else every pair fits */
    /* Far past the limit, the rows of SAMPLE_ROWS roots spread evenly over
     * the list tell at once: the atrium's 146,787 patches make about 4e9
     * links, refused in a second rather than after testing 2e10 pairs.  Only
     * an estimate eight times the limit is trusted; one above the limit is
     * checked by a count. */
    enum { SAMPLE_ROWS = 256 };
    if (limited && n > 4u * SAMPLE_ROWS) {
        uint64_t sampled = 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt) reduction(+ : sampled)
        for (uint32_t k = 0; k < SAMPLE_ROWS; k++)
            sampled += facing_row(s, (uint32_t)((uint64_t)k * n / SAMPLE_ROWS));
        estimate = sampled * n / SAMPLE_ROWS;
    }
    bool refused_on_estimate = estimate > 8u * max_links, too_many = refused_on_estimate;
    if (!too_many && estimate > max_links) {
        /* Likely too many: counted without making them (a facing test costs
         * far less than a link's form factor), up to the limit. */
        _Atomic uint64_t pairs = 0;
#pragma omp parallel for schedule(dynamic, 16) num_threads(nt)
        for (uint32_t i = 0; i < n; i++)
            if (!il_hr_stopping(s) && atomic_load(&pairs) <= max_links)
                atomic_fetch_add(&pairs, facing_row(s, i));
        too_many = atomic_load(&pairs) > max_links;
    }
    /* Then the links, with a running count that stops them as soon as it
     * passes the limit (by at most a row per thread). */
    _Atomic uint64_t made = 0;
    if (!too_many) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
        for (uint32_t i = 0; i < n; i++) {
            il_hr_pool *pool = &s->pools[omp_get_thread_num()];
            il_hr_elem *r = &s->roots[i];
            il_hr_watch_poll(s);
            il_hr_watch_root_done(s);
            if (!gathers(s, r) || il_hr_stopping(s) || (limited && atomic_load(&made) > max_links))
                continue;
            uint64_t row = 0;
            for (uint32_t j = 0; j < n && !pool->failed; j++) {
                if (j == i || !il_hr_facing(s, r, &s->roots[j]))
                    continue;
                il_hr_link *l = il_hr_link_make(s, pool, r, &s->roots[j]);
                if (!l)
                    break;
                il_hr_link_append(r, l);
                row++;
            }
            atomic_fetch_add(&made, row);
        }
    }
    if (limited && atomic_load(&made) > max_links)
        too_many = true;
    if (too_many) {
        char count[64];
        if (refused_on_estimate)
            snprintf(count, sizeof count, "about %llu", (unsigned long long)estimate);
        else
            snprintf(count, sizeof count, "more than %llu", (unsigned long long)max_links);
        return il_fail(err, IL_ERR_MEMORY,
                       "hr: %u patches make %s initial links, more than fit in half of this "
                       "machine's memory (%llu links, %.2f GB): hierarchical radiosity links "
                       "every pair of input polygons that face each other, so its memory grows "
                       "with their number squared; use --method radiosity (or pt) for a mesh "
                       "this large",
                       n, count, (unsigned long long)max_links, (double)max_links * link_bytes / 1e9);
    }
    if (pools_failed(s))
        return il_fail(err, IL_ERR_MEMORY, "hr: out of memory for the initial links");
    return reorder(s, err);
}

il_status il_hr_solve(const il_scene *scene, const il_patch_mesh *mesh, const il_hr_settings *set,
                      il_hr_solver *s, il_error *err)
{
    memset(s, 0, sizeof *s);
    s->scene = scene;
    s->mesh = mesh;
    s->set = *set;
    s->num_roots = mesh->num_patches;
    il_vec3 ext = v3_sub(scene->bounds_max, scene->bounds_min);
    s->diag = v3_length(ext);
    s->area_min = set->area_eps * s->diag * s->diag;
    s->plane_eps = 1e-5f * s->diag;
    il_patch_direct_kinds(scene, &s->delta_lights, &s->sky);
    il_hr_stats *st = &s->stats;
    st->patches = s->num_roots;
    il_hr_watch watch;
    il_hr_watch_start(s, &watch);
    il_hr_watch_phase(s, IL_HR_LINKING, 0, 0.0);

    double t0 = omp_get_wtime();
    il_status status = setup(s, err);
    st->seconds_setup = omp_get_wtime() - t0;
    if (status != IL_OK) {
        il_hr_solver_free(s);
        return status;
    }
    int nt = set->threads;
    uint32_t n = s->num_roots;
    double prev = total_energy(s), prev_delta = 0.0;
    bool converged = s->b_max <= 0.0f; /* no light: nothing to solve */
    bool stalled = false;
    for (uint32_t it = 0; it < set->max_iterations && s->b_max > 0.0f && !il_hr_stopping(s);
         it++) {
        il_hr_watch_phase(s, IL_HR_REFINING, it, 0.0);
        double t1 = omp_get_wtime();
        /* Split across processes: this refinement's new links computed
         * by shares and gathered first (hr_distrib.c). */
        il_status plan_st = il_distrib_on(set->distrib) ? il_hr_distrib_plan(s, err) : IL_OK;
        if (plan_st != IL_OK) {
            il_hr_solver_free(s);
            return plan_st;
        }
        /* One task per root, biggest first; a root's subtrees become tasks
         * of their own near the top (il_hr_refine_tree), so a scene of a
         * few big patches (the Cornell box's 17) still balances. */
#pragma omp parallel num_threads(nt)
#pragma omp single
        for (uint32_t i = 0; i < n; i++) {
            il_hr_elem *root = &s->roots[s->order[i]];
#pragma omp task firstprivate(root)
            {
                il_hr_refine_tree(s, root);
                il_hr_watch_root_done(s);
            }
        }
        double t2 = omp_get_wtime();
        st->seconds_refine += t2 - t1;
        if (pools_failed(s)) {
            il_hr_solver_free(s);
            return il_fail(err, IL_ERR_MEMORY, "hr: out of memory while refining links");
        }
        /* Stopped in the first refinement: some links have no visibility
         * yet, so none is gathered (il_hr_step_fn in illum.h). */
        if (it == 0 && il_hr_stopping(s))
            break;
        /* Sweeps until the links' system is solved (the same test as the
         * iterations', on the sweeps' changes) or a stop is asked. */
        double energy = prev, sweep_prev = prev, sweep_delta = 0.0;
        bool solved = false;
        /* Light that cannot leave (a closed room of albedo 1) makes every
         * sweep add as much as the last: radiosity's stall test
         * (rad_stall.h) on the sweeps' changes ends the solve. */
        il_rad_stall stall;
        il_rad_stall_start(&stall, 1);
        for (uint32_t k = 0; k < IL_HR_MAX_SWEEPS && !solved && !stalled && !(k > 0 && il_hr_stopping(s)); k++) {
#pragma omp parallel num_threads(nt)
            {
#pragma omp for schedule(dynamic, 1)
                for (uint32_t i = 0; i < n; i++)
                    il_hr_gather_root(&s->roots[s->order[i]]);
#pragma omp for schedule(dynamic, 1)
                for (uint32_t i = 0; i < n; i++)
                    il_hr_push_pull_root(&s->roots[s->order[i]]);
            }
            st->sweeps++;
            energy = total_energy(s);
            double d = fabs(energy - sweep_prev);
            solved = k > 0 && energy_left(sweep_delta, d) <= set->energy_eps * fabs(energy);
            stalled = !solved && il_rad_stalled(&stall, k + 1, d);
            sweep_delta = d;
            sweep_prev = energy;
        }
        st->seconds_gather += omp_get_wtime() - t2;
        st->iterations = it + 1;
        double delta = fabs(energy - prev);
        double change = it == 0 ? 1.0 : energy != 0.0 ? delta / fabs(energy) : 0.0;
        /* A stop cut this iteration's refinement or sweeps short: not converged. */
        converged = it > 0 && !il_hr_stopping(s) && !stalled &&
                    energy_left(prev_delta, delta) <= set->energy_eps * fabs(energy);
        st->energy_change = change;
        prev = energy;
        prev_delta = delta;
        il_hr_watch_phase(s, IL_HR_ITERATED, it + 1, change);
        if (converged || stalled)
            break;
        if (set->on_iteration && !set->on_iteration(s, set->on_iteration_user))
            break;
        if (reorder(s, err) != IL_OK) {
            il_hr_solver_free(s);
            return IL_ERR_MEMORY;
        }
    }

    uint64_t elems = 0, leaves = 0, links = 0;
    for (uint32_t i = 0; i < n; i++)
        count_tree(&s->roots[i], &elems, &leaves, &links);
    st->elements = elems;
    st->stopped = il_hr_stopping(s) && !converged && st->iterations < set->max_iterations;
    st->converged = converged;
    st->stalled = stalled;
    s->watch = NULL; /* it lived in this frame */
    st->leaves = leaves;
    st->links = links;
    st->peak_bytes = (uint64_t)n * (sizeof *s->roots + sizeof *s->order);
    for (int t = 0; t < nt; t++) {
        st->visibility_rays += s->pools[t].vis_rays;
        st->peak_bytes += s->pools[t].bytes;
    }
    return IL_OK;
}
