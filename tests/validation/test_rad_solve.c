/* Radiosity solvers against closed forms and against each other:
 * - a closed box whose walls all emit E with reflectance rho: every patch
 *   converges to L = E / (1 - rho) (the geometric series of a closed
 *   enclosure, Cohen & Wallace 1993, section 2.6), with both form-factor
 *   back-ends and all three solvers;
 * - shooting, Jacobi and Gauss-Seidel agree (Jacobi and Gauss-Seidel solve
 *   the same system: per patch within the tolerance; shooting transposes it
 *   through reciprocity, see test_solvers_agree);
 * - the same solution, bit for bit, with 1 and 2 threads and with a cache cap
 *   of one byte (every row recomputed) or the default;
 * - on_step is called and can stop the solve;
 * - a closed box of albedo 1 (no finite solution) stops as stalled with every
 *   solver, the shared kernel's Jacobi sweeps too, while albedo 0.999, slow
 *   to converge, converges with each (methods/radiosity/rad_stall.h). */
#include "kernel/kernel_radiosity_scene.h"
#include "methods/radiosity/rad_stall.h"
#include "rad_scenes.h"

static il_scene *emitting_box(float rho, float e)
{
    il_scene *s = new_scene();
    uint32_t m = diffuse_material(s, v3s(rho), v3s(e));
    const uint32_t mat[6] = {m, m, m, m, m, m};
    add_box_room(s, 1.0f, mat);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    return s;
}

/* Gathering uses row i for patch i; with rows that sum to 1 (a closed box)
 * L = E/(1-rho) is its exact fixed point, whatever the per-entry error, so
 * every patch must match.  Shooting uses row i to send light to every j
 * through reciprocity (F_ji = F_ij A_i/A_j), which estimated form factors
 * satisfy only approximately: ray-cast rows have Monte Carlo noise (it
 * shrinks as 1/sqrt(samples)), and the hemicube samples from the patch
 * centre, which is not reciprocal for neighbouring patches at the room's
 * edges (Cohen & Wallace 1993, section 4.9.5).  Energy is still conserved,
 * so the mean is exact; per patch the bound is looser for the hemicube. */
static void test_closed_box(float rho, il_form_factor_method ffm, il_radiosity_solver solver,
                            uint32_t samples, double patch_tol)
{
    const float e = 1.0f;
    il_scene *s = emitting_box(rho, e);
    il_radiosity_desc rad = {.subdivisions = 2, .form_factors = ffm, .solver = solver,
                             .tolerance = 1e-3f, .ray_samples = samples};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 2, .radiosity = &rad};
    rad_case c;
    CHECK_OK(rad_case_run(s, &rd, 0, &c), &g_err);
    if (c.mesh) {
        CHECK(c.mesh->num_patches == 6 * 16);
        double expect = e / (1.0 - rho), worst = 0.0, mean = 0.0, area = 0.0;
        for (uint32_t i = 0; i < c.mesh->num_patches; i++) {
            il_vec3 L = c.sol.radiance[i];
            CHECK(L.x == L.y && L.y == L.z);
            worst = fmax(worst, fabs(L.x - expect) / expect);
            mean += c.mesh->patches[i].area * L.y;
            area += c.mesh->patches[i].area;
        }
        printf("closed box rho %.1f ff %d solver %d: %u patches, %u steps, mean %.5f (expect %.5f), "
               "worst patch %.3f%%\n",
               (double)rho, (int)ffm, (int)solver, c.mesh->num_patches, c.sol.steps, mean / area,
               expect, 100.0 * worst);
        CHECK_REL(mean / area, expect, 0.002);
        CHECK(worst < patch_tol);
        CHECK(c.sol.unshot_fraction < 1e-3);
        CHECK(!c.sol.stalled && !c.stats.stalled);
        if (solver != IL_SOLVER_SHOOTING)
            CHECK(c.stats.rows_computed == c.mesh->num_patches);
    }
    rad_case_free(&c);
    il_scene_release(s);
}

/* A mesh large enough for shooting batches of more than 8 (over 36,864
 * patches: one shooter a step per 4096 patches): still the closed box's
 * E / (1 - rho) on average, and the same bits with 1 and 2 threads. */
static void test_large_batches(void)
{
    const float rho = 0.3f, e = 1.0f;
    il_scene *s = emitting_box(rho, e);
    il_radiosity_desc rad = {.patch_size = 0.012f, .form_factors = IL_FF_RAYCAST, .ray_samples = 64};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 1, .radiosity = &rad};
    rad_case a, b;
    CHECK_OK(rad_case_run(s, &rd, 0, &a), &g_err);
    rd.threads = 2;
    CHECK_OK(rad_case_run(s, &rd, 0, &b), &g_err);
    if (a.mesh && b.mesh) {
        uint32_t n = a.mesh->num_patches;
        uint32_t batch = n / 4096u;
        CHECK(n > 36864 && b.mesh->num_patches == n);
        double mean = 0.0, area = 0.0;
        for (uint32_t i = 0; i < n; i++) {
            mean += a.mesh->patches[i].area * a.sol.radiance[i].y;
            area += a.mesh->patches[i].area;
        }
        printf("closed box, %u patches: %u shots in batches of %u, mean %.5f (expect %.5f), "
               "unshot %.4f\n", n, a.sol.steps, batch, mean / area, e / (1.0 - rho),
               a.sol.unshot_fraction);
        /* Unshot power below 1% of the emitted: at most 1% of the light
         * is missing. */
        CHECK(mean / area <= e / (1.0 - rho) * 1.001 && mean / area >= e / (1.0 - rho) * 0.99);
        CHECK(a.sol.unshot_fraction < 0.01 && !a.sol.stalled);
        CHECK(a.sol.steps > 0 && a.sol.steps % batch == 0);
        CHECK(a.sol.steps == b.sol.steps);
        CHECK(memcmp(a.sol.radiance, b.sol.radiance, n * sizeof(il_vec3)) == 0);
    }
    rad_case_free(&a);
    rad_case_free(&b);
    il_scene_release(s);
}

static il_render_desc room_desc(il_radiosity_desc *rad, il_radiosity_solver solver, int threads)
{
    memset(rad, 0, sizeof *rad);
    rad->subdivisions = 2;
    rad->form_factors = IL_FF_RAYCAST;
    rad->ray_samples = 1024;
    rad->solver = solver;
    rad->tolerance = 1e-4f;
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = threads, .seed = 7,
                         .radiosity = rad};
    return rd;
}

/* Jacobi and Gauss-Seidel solve the same system from the same rows: they
 * agree per patch within the tolerance.  Shooting solves it through
 * reciprocity (see test_closed_box), so with ray-cast rows it agrees up to
 * their noise: with 65,536 rays per patch, each surface's mean within 1%. */
static void test_solvers_agree(void)
{
    il_scene *s = coloured_room();
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    rad_case c[3];
    const il_radiosity_solver solvers[3] = {IL_SOLVER_SHOOTING, IL_SOLVER_JACOBI,
                                            IL_SOLVER_GAUSS_SEIDEL};
    for (int k = 0; k < 3; k++) {
        il_radiosity_desc rad;
        il_render_desc rd = room_desc(&rad, solvers[k], 2);
        rad.ray_samples = 65536;
        CHECK_OK(rad_case_run(s, &rd, 0, &c[k]), &g_err);
    }
    if (c[0].mesh && c[1].mesh && c[2].mesh) {
        const il_patch_mesh *m = c[0].mesh;
        CHECK(m->num_patches >= 100 && m->num_patches <= 400);
        /* Indirect light matters here: the walls are well above direct. */
        double p_direct = 0.0, p_total = 0.0;
        for (uint32_t i = 0; i < m->num_patches; i++) {
            if (!v3_is_zero(m->patches[i].emission))
                continue;
            p_direct += m->patches[i].area * il_luminance(c[0].sol.direct[i]);
            p_total += m->patches[i].area * il_luminance(c[0].sol.radiance[i]);
        }
        CHECK(p_direct == 0.0 && p_total > 0.0);

        double gd = rad_max_rel_diff(m, c[2].sol.radiance, c[1].sol.radiance, 1e-3);
        printf("gauss-seidel vs jacobi: worst patch %.2e, %u vs %u sweeps\n", gd, c[2].sol.steps,
               c[1].sol.steps);
        CHECK(gd < 1e-3);
        /* Gauss-Seidel needs fewer sweeps than Jacobi (Cohen & Wallace 5.3). */
        CHECK(c[2].sol.steps < c[1].sol.steps);

        double pd = rad_power_diff(m, c[0].sol.radiance, c[2].sol.radiance);
        printf("shooting vs gauss-seidel: power diff %.2e (%u shots)\n", pd, c[0].sol.steps);
        CHECK(pd < 0.01);
        for (uint32_t sf = 0; sf < m->num_surfaces; sf++) {
            double a = 0.0, b = 0.0;
            for (uint32_t i = 0; i < m->num_patches; i++)
                if (m->patches[i].surface == sf) {
                    a += m->patches[i].area * il_luminance(c[0].sol.radiance[i]);
                    b += m->patches[i].area * il_luminance(c[2].sol.radiance[i]);
                }
            printf("  surface %u: shooting %.5f gauss-seidel %.5f\n", sf, a, b);
            CHECK_REL(a, b, 0.01);
        }

        /* The red wall bleeds red onto the floor next to it. */
        double fr_red = 0, fr_green = 0;
        for (uint32_t i = 0; i < m->num_patches; i++) {
            const il_patch *p = &m->patches[i];
            if (p->normal.y > 0.9f && p->center.y < 0.01f) {
                il_vec3 L = c[0].sol.radiance[i];
                if (p->center.x < 0.25f)
                    fr_red += L.x / L.y;
                if (p->center.x > 0.75f)
                    fr_green += L.x / L.y;
            }
        }
        CHECK(fr_red > fr_green);
    }
    for (int k = 0; k < 3; k++)
        rad_case_free(&c[k]);
    il_scene_release(s);
}

/* Bit-identical with 1 and 2 threads, and with every row recomputed. */
static void test_determinism(void)
{
    il_scene *s = coloured_room();
    il_light_desc point = {.type = IL_LIGHT_POINT, .position = v3(0.3f, 0.6f, 0.4f),
                           .intensity = v3(0.5f, 0.4f, 0.3f)};
    CHECK_OK(il_scene_add_light(s, &point, &g_err), &g_err);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    const il_radiosity_solver solvers[3] = {IL_SOLVER_SHOOTING, IL_SOLVER_JACOBI,
                                            IL_SOLVER_GAUSS_SEIDEL};
    const il_form_factor_method methods[2] = {IL_FF_HEMICUBE, IL_FF_RAYCAST};
    for (int k = 0; k < 3; k++) {
        for (int ffm = 0; ffm < 2; ffm++) {
            rad_case a, b, tiny;
            il_radiosity_desc rad;
            il_render_desc rd = room_desc(&rad, solvers[k], 1);
            rad.form_factors = methods[ffm];
            rad.hemicube_resolution = 64;
            rad.tolerance = 1e-3f;
            CHECK_OK(rad_case_run(s, &rd, 0, &a), &g_err);
            rd.threads = 2;
            CHECK_OK(rad_case_run(s, &rd, 0, &b), &g_err);
            CHECK_OK(rad_case_run(s, &rd, 1, &tiny), &g_err);
            if (a.mesh && b.mesh && tiny.mesh && a.mesh->num_patches == b.mesh->num_patches &&
                a.mesh->num_patches == tiny.mesh->num_patches) {
                size_t bytes = a.mesh->num_patches * sizeof(il_vec3);
                CHECK(memcmp(a.sol.direct, b.sol.direct, bytes) == 0);
                CHECK(memcmp(a.sol.radiance, b.sol.radiance, bytes) == 0);
                CHECK(memcmp(a.sol.radiance, tiny.sol.radiance, bytes) == 0);
                CHECK(a.sol.steps == b.sol.steps && a.sol.steps == tiny.sol.steps);
                /* With the default cap every row is computed once; with one
                 * byte none is kept, so shots and sweeps recompute theirs. */
                CHECK(a.stats.rows_computed <= a.mesh->num_patches);
                CHECK(tiny.stats.cache_bytes == 0);
                CHECK(a.stats.cache_bytes > 0);
                if (k != IL_SOLVER_SHOOTING && tiny.sol.steps > 1)
                    CHECK(tiny.stats.rows_computed == (uint64_t)tiny.sol.steps * a.mesh->num_patches);
                if (k == IL_SOLVER_SHOOTING)
                    CHECK(tiny.stats.rows_computed == tiny.sol.steps);
            } else {
                CHECK(!"determinism runs failed");
            }
            rad_case_free(&a);
            rad_case_free(&b);
            rad_case_free(&tiny);
        }
    }
    il_scene_release(s);
}

typedef struct step_log {
    uint32_t calls, last_step, stop_after;
    double last_fraction;
    bool monotone, finite;
} step_log;

static bool on_step(const il_radiosity_progress *p, void *user)
{
    step_log *log = user;
    if (log->calls > 0 && p->step <= log->last_step)
        log->monotone = false;
    for (uint32_t i = 0; i < 3 * p->num_patches; i++)
        if (!isfinite(p->radiance[i]) || p->radiance[i] < 0.0f)
            log->finite = false;
    log->calls++;
    log->last_step = p->step;
    log->last_fraction = p->unshot_fraction;
    return log->stop_after == 0 || log->calls < log->stop_after;
}

static void test_on_step(void)
{
    il_scene *s = coloured_room();
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    for (int k = 0; k < 3; k++) {
        step_log log = {.monotone = true, .finite = true, .stop_after = 3};
        il_radiosity_desc rad;
        il_render_desc rd = room_desc(&rad, (il_radiosity_solver)k, 2);
        rad.on_step = on_step;
        rad.on_step_user = &log;
        rad_case c;
        CHECK_OK(rad_case_run(s, &rd, 0, &c), &g_err);
        CHECK(log.calls == 3);
        CHECK(log.monotone && log.finite);
        CHECK(c.sol.steps == log.last_step);
        CHECK_NEAR(c.sol.unshot_fraction, log.last_fraction, 0.0);
        CHECK(c.sol.unshot_fraction > 1e-4);
        if (k == IL_SOLVER_SHOOTING) {
            CHECK(c.sol.steps == 24); /* three batches of 8 shooters */
            CHECK(c.sol.ambient.x > 0.0f);
        }
        rad_case_free(&c);

        /* max_steps caps the shots (shooting) or sweeps (gathering). */
        rad.on_step = NULL;
        rad.max_steps = 5;
        CHECK_OK(rad_case_run(s, &rd, 0, &c), &g_err);
        CHECK(c.sol.steps == 5);
        rad_case_free(&c);
    }
    il_scene_release(s);
}

/* Albedo 1 in a closed box: every ray-cast row sums to 1, so no light
 * leaves and the measure cannot fall.  The solve must stop by itself, as
 * stalled, after its third window (the first is left out, the second gives
 * the reference): 3 W n shots (plus the last batch of 8) or 3 W sweeps,
 * W = IL_RAD_STALL_WINDOW. */
static void test_stall(il_radiosity_solver solver)
{
    il_scene *s = emitting_box(1.0f, 1.0f);
    il_radiosity_desc rad = {.subdivisions = 2, .form_factors = IL_FF_RAYCAST, .solver = solver,
                             .ray_samples = 256};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .threads = 2, .radiosity = &rad};
    rad_case c;
    CHECK_OK(rad_case_run(s, &rd, 0, &c), &g_err);
    if (c.mesh) {
        uint32_t n = c.mesh->num_patches;
        printf("closed box rho 1 solver %d: stalled %d after %u steps, unshot %.6f\n", (int)solver,
               (int)c.stats.stalled, c.sol.steps, c.sol.unshot_fraction);
        CHECK(c.sol.stalled && c.stats.stalled);
        CHECK(c.sol.steps <= (solver == IL_SOLVER_SHOOTING ? 3 * IL_RAD_STALL_WINDOW * n + 8 : 3 * IL_RAD_STALL_WINDOW));
        CHECK(c.sol.unshot_fraction > 0.99);
        if (solver == IL_SOLVER_JACOBI) {
            /* The shared kernel (the GPU's solve, compiled by gcc) too. */
            il_krad k;
            CHECK_OK(il_krad_build(c.mesh, c.sol.direct, 64, 1, &k, &g_err), &g_err);
            ilk_vec3 *L = malloc(sizeof *L * n);
            uint32_t steps = 0;
            double frac = 0.0;
            bool stalled = false;
            CHECK_OK(il_krad_solve(&k, 0.01f, 0, L, &steps, &frac, &stalled, &g_err), &g_err);
            printf("  shared kernel: stalled %d after %u sweeps, change %.6f\n", (int)stalled, steps, frac);
            CHECK(stalled && steps == 3 * IL_RAD_STALL_WINDOW);
            free(L);
            il_krad_free(&k);
        }
    }
    rad_case_free(&c);
    il_scene_release(s);

    /* Albedo 0.999: slow (the measure falls about 1% per window of 10 n
     * shots or 10 sweeps) but finite: it must converge, not stall, down to
     * a tolerance of 1e-4, where the change a sweep makes (0.1 of L = 1000)
     * is below 2 ulps of L: measured as a difference of floats it stuck at
     * 4 ulps, and the gathering solves stopped as stalled. */
    s = emitting_box(0.999f, 1.0f);
    rad.tolerance = 1e-4f;
    CHECK_OK(rad_case_run(s, &rd, 0, &c), &g_err);
    if (c.mesh) {
        printf("closed box rho 0.999 solver %d: stalled %d after %u steps, unshot %.6f\n", (int)solver,
               (int)c.stats.stalled, c.sol.steps, c.sol.unshot_fraction);
        CHECK(!c.sol.stalled && c.sol.unshot_fraction < 1e-4);
        if (solver == IL_SOLVER_JACOBI) {
            /* The shared kernel's float sweeps (the GPU's) converge too. */
            il_krad k;
            CHECK_OK(il_krad_build(c.mesh, c.sol.direct, 64, 1, &k, &g_err), &g_err);
            ilk_vec3 *L = malloc(sizeof *L * c.mesh->num_patches);
            uint32_t steps = 0;
            double frac = 0.0;
            bool stalled = true;
            CHECK_OK(il_krad_solve(&k, 1e-4f, 0, L, &steps, &frac, &stalled, &g_err), &g_err);
            printf("  shared kernel: stalled %d after %u sweeps, change %.6f\n", (int)stalled, steps, frac);
            CHECK(!stalled && frac < 1e-4);
            free(L);
            il_krad_free(&k);
        }
    }
    rad_case_free(&c);
    il_scene_release(s);
}

int main(void)
{
    /* Gathering: exact per patch with either back-end. */
    test_closed_box(0.5f, IL_FF_RAYCAST, IL_SOLVER_JACOBI, 1024, 0.01);
    test_closed_box(0.8f, IL_FF_RAYCAST, IL_SOLVER_JACOBI, 1024, 0.01);
    test_closed_box(0.8f, IL_FF_RAYCAST, IL_SOLVER_GAUSS_SEIDEL, 1024, 0.01);
    test_closed_box(0.5f, IL_FF_HEMICUBE, IL_SOLVER_JACOBI, 0, 0.01);
    test_closed_box(0.8f, IL_FF_HEMICUBE, IL_SOLVER_GAUSS_SEIDEL, 0, 0.01);
    /* Shooting: per patch as good as the rows' reciprocity. */
    test_closed_box(0.5f, IL_FF_RAYCAST, IL_SOLVER_SHOOTING, 16384, 0.01);
    test_closed_box(0.8f, IL_FF_RAYCAST, IL_SOLVER_SHOOTING, 65536, 0.01);
    test_closed_box(0.5f, IL_FF_HEMICUBE, IL_SOLVER_SHOOTING, 0, 0.05);
    test_closed_box(0.8f, IL_FF_HEMICUBE, IL_SOLVER_SHOOTING, 0, 0.05);
    test_solvers_agree();
    test_determinism();
    test_large_batches();
    test_on_step();
    test_stall(IL_SOLVER_SHOOTING);
    test_stall(IL_SOLVER_JACOBI);
    test_stall(IL_SOLVER_GAUSS_SEIDEL);
    return check_report();
}
