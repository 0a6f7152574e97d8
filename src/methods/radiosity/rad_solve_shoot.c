/* Progressive refinement by shooting (Cohen, Chen, Wallace, Greenberg 1988,
 * "A Progressive Refinement Approach to Fast Radiosity Image Generation").
 *
 * Every patch starts with radiance = unshot = direct (its emission plus the
 * light of point/spot/directional lights and the sky).  A shot from patch i
 * distributes its unshot radiance dL_i to every patch j it sees (section 3,
 * "shooting"; with reciprocity A_j F_ji = A_i F_ij):
 *     dL_j += rho_j * F_ji * dL_i = rho_j * F_ij * (A_i / A_j) * dL_i,
 * and sets dL_i = 0.  The patches with the most unshot power A_i lum(dL_i)
 * go first (section 3.1, "sorting").  The solve ends when the unshot power
 * is under the tolerance of the initial power and, with view weights, the
 * view measure (view_fraction below) is under it too.
 *
 * Parallelism and determinism: each step takes a batch of shooters whose
 * size depends on the patch count only (shoot_batch), computes their rows
 * in parallel, then shoots them one after another in order, each with its
 * unshot radiance at that moment.  So the result does not depend on the
 * number of threads.
 *
 * Display (section 3.2, "ambient term"): ambient = R * sum_i(dL_i A_i) /
 * sum_i(A_i), with R = 1 / (1 - rho_avg) the overall interreflection factor,
 * rho_avg the area-weighted mean reflectance; a patch shows L_i + rho_i *
 * ambient.  Only handed to the callback (and kept in sol->ambient); the
 * result itself has no ambient term. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/radiosity/rad_solve.h"

#define IL_RAD_SHOOT_BATCH_MIN 8u
#define IL_RAD_SHOOT_BATCH_MAX 64u

/* Shooters per step: one per 4096 patches, at least 8 (so below 36,864
 * patches always 8) and at most 64.
 * Each step scans every patch (and fills the display array), one thread's
 * work while the others wait; on a large mesh a batch of 8 rows leaves that
 * serial scan a large share of the time (15% of the atrium's 150,848-patch
 * solve, with the other thread idle meanwhile). */
static uint32_t shoot_batch(uint32_t num_patches)
{
    uint32_t b = num_patches / 4096u;
    return b < IL_RAD_SHOOT_BATCH_MIN ? IL_RAD_SHOOT_BATCH_MIN
         : b > IL_RAD_SHOOT_BATCH_MAX ? IL_RAD_SHOOT_BATCH_MAX
                                      : b;
}

typedef struct shoot_scan {
    uint32_t shooter[IL_RAD_SHOOT_BATCH_MAX]; /* largest unshot power first */
    uint32_t batch;                       /* shooters wanted (shoot_batch) */
    uint32_t count;
    double unshot_power;                  /* sum_i A_i lum(dL_i) */
    double unshot_seen;                   /* sum_i g_i lum(dL_i) (view_measure) */
    il_vec3 unshot_sum;                   /* sum_i A_i dL_i per channel */
} shoot_scan;

/* One pass over the patches: the total unshot power and the patches with the
 * most of it (ties go to the lower index, so the choice is deterministic). */
static void scan_unshot(const il_patch_mesh *mesh, const il_vec3 *unshot, const float *g,
                        shoot_scan *s)
{
    double top[IL_RAD_SHOOT_BATCH_MAX];
    uint32_t batch = s->batch;
    double sum_r = 0.0, sum_g = 0.0, sum_b = 0.0, total = 0.0, seen = 0.0;
    s->count = 0;
    for (uint32_t i = 0; i < mesh->num_patches; i++) {
        double a = mesh->patches[i].area;
        il_vec3 u = unshot[i];
        double lu = il_luminance(u), p = a * lu;
        if (g)
            seen += g[i] * lu;
        sum_r += a * u.x;
        sum_g += a * u.y;
        sum_b += a * u.z;
        total += p;
        if (!(p > 0.0))
            continue;
        if (s->count == batch && !(p > top[batch - 1]))
            continue;
        /* Insertion into the sorted list of the best. */
        uint32_t k = s->count < batch ? s->count++ : batch - 1;
        while (k > 0 && p > top[k - 1]) {
            top[k] = top[k - 1];
            s->shooter[k] = s->shooter[k - 1];
            k--;
        }
        top[k] = p;
        s->shooter[k] = i;
    }
    s->unshot_power = total;
    s->unshot_seen = seen;
    s->unshot_sum = v3((float)sum_r, (float)sum_g, (float)sum_b);
}

/* Shoots patch i's unshot radiance along its row. */
static void shoot(const il_patch_mesh *mesh, const il_ff_row *row, uint32_t i, il_rad_solution *sol)
{
    il_vec3 u = sol->unshot[i];
    sol->unshot[i] = v3s(0.0f);
    float ai = mesh->patches[i].area;
    for (uint32_t k = 0; k < row->count; k++) {
        uint32_t j = row->index[k];
        if (j == i)
            continue; /* a planar patch does not see itself */
        const il_patch *pj = &mesh->patches[j];
        if (!(pj->area > 0.0f))
            continue;
        float s = row->value[k] * ai / pj->area;
        il_vec3 d = v3_scale(v3_mul(pj->rho, u), s);
        sol->radiance[j] = v3_add(sol->radiance[j], d);
        sol->unshot[j] = v3_add(sol->unshot[j], d);
    }
}

/* The view measure (rad_view.c): how much the light still unshot would add
 * to what the camera sees in one bounce, over what it sees now,
 *
 *     sum_i g_i lum(dL_i) / sum_j w_j lum(L_j),   g_i = sum_j w_j lum(rho_j) F_ji,
 *
 * with w_j the share of the view patch j fills: a shot of dL_i adds
 * rho_j F_ji dL_i to patch j (F_ji from j's own form-factor row).  g is the
 * view's importance (Smits et al. 1992, importance-driven radiosity), made
 * once from the rows of the patches seen. */
typedef struct view_measure {
    uint32_t n;
    uint32_t *patch;           /* the patches the camera sees */
    float *weight;             /* their shares of the view */
    float *g;                  /* per patch: its importance to the view (NULL: no measure) */
} view_measure;

static void view_free(view_measure *v)
{
    free(v->patch);
    free(v->weight);
    free(v->g);
}

static il_status view_make(const il_patch_mesh *mesh, const il_ff *ff, il_ff_cache *cache,
                           il_rad_rows *rows, const float *weight, il_radiosity_stats *stats,
                           view_measure *v, il_error *err)
{
    memset(v, 0, sizeof *v);
    if (!weight)
        return IL_OK;
    uint32_t n = 0;
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        n += weight[i] > 0.0f;
    v->patch = il_malloc((n ? n : 1) * sizeof *v->patch, err);
    v->weight = il_malloc((n ? n : 1) * sizeof *v->weight, err);
    v->g = il_calloc(mesh->num_patches ? mesh->num_patches : 1, sizeof *v->g, err);
    if (!v->patch || !v->weight || !v->g) {
        view_free(v);
        return IL_ERR_MEMORY;
    }
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        if (weight[i] > 0.0f) {
            v->patch[v->n] = i;
            v->weight[v->n++] = weight[i];
        }
    for (uint32_t base = 0; base < v->n; base += rows->cap) {
        uint32_t count = v->n - base < rows->cap ? v->n - base : rows->cap;
        il_status st = il_rad_rows_fetch(rows, ff, cache, v->patch + base, 0, count, stats, err);
        if (st != IL_OK) {
            view_free(v);
            return st;
        }
        for (uint32_t k = 0; k < count; k++) {
            uint32_t j = v->patch[base + k];
            float c = v->weight[base + k] * il_luminance(mesh->patches[j].rho);
            const il_ff_row *row = rows->row[k];
            for (uint32_t e = 0; e < row->count; e++)
                v->g[row->index[e]] += c * row->value[e];
        }
    }
    return IL_OK;
}

static double view_fraction(const view_measure *v, const il_vec3 *radiance, double unshot_seen)
{
    if (!v->g)
        return 0.0;
    double seen = 0.0;
    for (uint32_t k = 0; k < v->n; k++)
        seen += v->weight[k] * (double)il_luminance(radiance[v->patch[k]]);
    return seen > 0.0 ? unshot_seen / seen : 0.0;
}

/* R = 1 / (1 - rho_avg) per channel (Cohen et al. 1988, eq. 6). */
static il_vec3 interreflection(const il_patch_mesh *mesh)
{
    double r = 0.0, g = 0.0, b = 0.0, area = 0.0;
    for (uint32_t i = 0; i < mesh->num_patches; i++) {
        const il_patch *p = &mesh->patches[i];
        r += (double)p->area * p->rho.x;
        g += (double)p->area * p->rho.y;
        b += (double)p->area * p->rho.z;
        area += p->area;
    }
    if (!(area > 0.0))
        return v3s(1.0f);
    /* A white closed room would make R infinite: cap rho_avg. */
    double rr = fmin(r / area, 0.999), gg = fmin(g / area, 0.999), bb = fmin(b / area, 0.999);
    return v3((float)(1.0 / (1.0 - rr)), (float)(1.0 / (1.0 - gg)), (float)(1.0 / (1.0 - bb)));
}

static il_vec3 ambient_term(il_vec3 R, il_vec3 unshot_sum, double total_area)
{
    float inv = total_area > 0.0 ? (float)(1.0 / total_area) : 0.0f;
    return v3_scale(v3_mul(R, unshot_sum), inv);
}

il_status il_rad_solve_shooting(const il_patch_mesh *mesh, const il_ff *ff, il_ff_cache *cache,
                                const il_rad_settings *settings, il_rad_solution *sol,
                                il_radiosity_stats *stats, il_error *err)
{
    uint32_t n = mesh->num_patches;
    double t0 = omp_get_wtime();
    for (uint32_t i = 0; i < n; i++)
        sol->radiance[i] = sol->unshot[i] = sol->direct[i];
    sol->steps = 0;
    sol->ambient = v3s(0.0f);

    double total_area = 0.0;
    for (uint32_t i = 0; i < n; i++)
        total_area += mesh->patches[i].area;
    il_vec3 R = interreflection(mesh);
    double p0 = il_rad_power(mesh, sol->direct);

    float *display = NULL;
    if (settings->on_step) {
        display = il_malloc((size_t)(n ? n : 1) * 3 * sizeof(float), err);
        if (!display)
            return IL_ERR_MEMORY;
    }
    il_rad_rows rows;
    shoot_scan scan = {.batch = shoot_batch(n)};
    il_status st = il_rad_rows_init(&rows, ff, scan.batch, settings->threads, err);
    if (st != IL_OK) {
        free(display);
        return st;
    }
    rows.distrib = settings->distrib;
    view_measure view;
    st = view_make(mesh, ff, cache, &rows, settings->view_weight, stats, &view, err);
    if (st != IL_OK) {
        il_rad_rows_free(&rows);
        free(display);
        return st;
    }

    scan_unshot(mesh, sol->unshot, view.g, &scan);
    double frac = p0 > 0.0 ? scan.unshot_power / p0 : 0.0;
    double vfrac = view_fraction(&view, sol->radiance, scan.unshot_seen);
    uint32_t steps = 0;
    il_rad_stall stall;
    il_rad_stall_start(&stall, n);
    sol->stalled = false;
    while (p0 > 0.0 && (frac >= settings->tolerance || vfrac >= settings->tolerance) &&
           scan.count > 0 && (settings->max_steps == 0 || steps < settings->max_steps)) {
        uint32_t batch = scan.count;
        if (settings->max_steps && settings->max_steps - steps < batch)
            batch = settings->max_steps - steps;
        st = il_rad_rows_fetch(&rows, ff, cache, scan.shooter, 0, batch, stats, err);
        if (st != IL_OK)
            break;
        for (uint32_t k = 0; k < batch; k++)
            shoot(mesh, rows.row[k], scan.shooter[k], sol);
        steps += batch;
        scan_unshot(mesh, sol->unshot, view.g, &scan);
        frac = scan.unshot_power / p0;
        vfrac = view_fraction(&view, sol->radiance, scan.unshot_seen);
        if (settings->on_step &&
            !il_rad_report_step(mesh, settings, sol->radiance,
                                ambient_term(R, scan.unshot_sum, total_area), display, steps,
                                frac, omp_get_wtime() - t0))
            break;
        double measure = frac > vfrac ? frac : vfrac;
        if (measure >= settings->tolerance && (sol->stalled = il_rad_stalled(&stall, steps, measure)))
            break;
    }
    sol->steps = steps;
    sol->unshot_fraction = frac;
    sol->view_fraction = vfrac;
    sol->ambient = ambient_term(R, scan.unshot_sum, total_area);
    size_t working = il_rad_rows_bytes(&rows) + (display ? (size_t)n * 3 * sizeof(float) : 0);
    if (working > stats->peak_bytes)
        stats->peak_bytes = working;
    il_rad_rows_free(&rows);
    free(display);
    view_free(&view);
    return st;
}
