/* il_hr_desc.on_step: the progress reports and a stop asked at each point
 * of the solve (illum.h, il_hr_step_fn):
 *   - reports come in order (linking, then per iteration refining and
 *     iterated), on the calling thread, with the iteration counts and the
 *     energy change the convergence test uses;
 *   - stopped while linking: no light exchanged, every leaf's radiance is
 *     its emission exactly;
 *   - stopped after iteration 1 or at the start of iteration 2's refinement:
 *     that many iterations, and a reflected energy that lies between no
 *     exchange and the converged solution (Jacobi iterations from the
 *     emission only add light);
 *   - stopped in the middle of a refinement (whenever the 0.1 s report
 *     falls): a valid, finite solution of at most the converged energy;
 *   - a stop that comes after the last iteration is not called one. */
#include <math.h>
#include "hr_scenes.h"
#include "step_watch.h"

typedef struct watcher {
    il_hr_phase stop_phase;        /* stop at the first report of this phase ... */
    uint32_t stop_iterations;      /* ... with this many iterations done ... */
    uint32_t stop_report;          /* ... and this many such reports before it */
    uint32_t seen;                 /* reports matching phase and iterations */
    step_watch sw;
    il_hr_phase last_phase;
    uint32_t last_iterations;
    double last_seconds, first_change;
} watcher;

static bool on_step(const il_hr_progress *p, void *user)
{
    watcher *w = user;
    /* The first report is the linking's; then phases and iterations never
     * go back, nor does time. */
    bool in_order = p->phase == IL_HR_LINKING;
    if (w->sw.calls > 0) {
        bool later = p->iterations > w->last_iterations ||
                     (p->iterations == w->last_iterations && p->phase >= w->last_phase) ||
                     (p->phase == IL_HR_REFINING && w->last_phase == IL_HR_ITERATED &&
                      p->iterations == w->last_iterations);
        in_order = later && p->seconds >= w->last_seconds && p->roots_done <= p->num_roots;
    }
    step_watch_report(&w->sw, in_order);
    if (p->phase == IL_HR_ITERATED && p->iterations == 1)
        w->first_change = p->energy_change;
    w->last_phase = p->phase;
    w->last_iterations = p->iterations;
    w->last_seconds = p->seconds;
    if (p->phase == w->stop_phase && p->iterations == w->stop_iterations)
        return w->seen++ < w->stop_report;
    return true;
}

/* Solves with a watcher; returns the reflected energy sum A lum(B - Le)
 * over the leaves and whether every leaf's radiance is its emission. */
typedef struct outcome {
    il_hr_stats stats;
    double reflected;
    bool emission_only, finite;
    watcher w;
} outcome;

static void add_leaf(const il_hr_elem *e, void *user)
{
    outcome *o = user;
    il_vec3 r = v3_sub(e->radiance, e->emit);
    o->reflected += (double)e->area * il_luminance(r);
    if (e->radiance.x != e->emit.x || e->radiance.y != e->emit.y || e->radiance.z != e->emit.z)
        o->emission_only = false;
    if (!isfinite(r.x) || !isfinite(r.y) || !isfinite(r.z))
        o->finite = false;
}

static outcome solve(const il_scene *s, il_hr_desc hd, watcher w, int threads)
{
    outcome o = {.emission_only = true, .finite = true};
    o.w = w;
    step_watch_begin(&o.w.sw);
    hd.on_step = on_step;
    hd.on_step_user = &o.w;
    il_render_desc rd = {.method = IL_METHOD_HR, .threads = threads, .hr = &hd};
    hr_case c;
    CHECK_OK(hr_case_run(s, &rd, &c), &g_err);
    o.stats = c.solver.stats;
    for (uint32_t i = 0; i < c.solver.num_roots; i++)
        hr_visit_leaves(&c.solver.roots[i], add_leaf, &o);
    hr_case_free(&c);
    step_watch_check(&o.w.sw);
    CHECK(o.finite);
    return o;
}

int main(void)
{
    il_scene *s = hr_room(false, true);
    CHECK_OK(il_scene_commit(s, &g_err), &g_err);
    const il_hr_desc hd = {.energy_eps = 1e-4f};
    const watcher never = {.stop_phase = (il_hr_phase)99};

    outcome full = solve(s, hd, never, 2);
    hr_print_stats("converged", &full.stats);
    CHECK(!full.stats.stopped);
    CHECK(full.stats.iterations >= 3);
    CHECK(full.reflected > 0.0);
    CHECK(full.w.sw.calls >= 1 + 2 * full.stats.iterations);
    CHECK(full.w.last_phase == IL_HR_ITERATED && full.w.last_iterations == full.stats.iterations);
    CHECK_NEAR(full.w.first_change, 1.0, 0.0);

    /* Stopped while linking: nothing exchanged. */
    outcome linking = solve(s, hd, (watcher){.stop_phase = IL_HR_LINKING}, 2);
    CHECK(linking.stats.stopped && linking.stats.iterations == 0);
    CHECK(linking.emission_only);
    CHECK(linking.w.sw.calls == 1);

    /* Stopped at the start of the first refinement: the same. */
    outcome refine1 = solve(s, hd, (watcher){.stop_phase = IL_HR_REFINING}, 2);
    CHECK(refine1.stats.stopped && refine1.stats.iterations == 0);
    CHECK(refine1.emission_only);

    /* Stopped after the first iteration: the direct light of the lamp. */
    outcome it1 = solve(s, hd, (watcher){.stop_phase = IL_HR_ITERATED, .stop_iterations = 1}, 2);
    printf("reflected energy: converged %.5f, after 1 iteration %.5f\n", full.reflected,
           it1.reflected);
    CHECK(it1.stats.stopped && it1.stats.iterations == 1);
    CHECK(it1.reflected > 0.0 && it1.reflected < full.reflected);

    /* Stopped as the second refinement starts: no link of it is refined,
     * but the iteration's gather and push-pull run. */
    outcome it2 = solve(s, hd, (watcher){.stop_phase = IL_HR_REFINING, .stop_iterations = 1}, 2);
    printf("stopped at the second refinement: %.5f, %llu links (converged %llu)\n", it2.reflected,
           (unsigned long long)it2.stats.links, (unsigned long long)full.stats.links);
    CHECK(it2.stats.stopped && it2.stats.iterations == 2);
    CHECK(it2.reflected > it1.reflected && it2.reflected <= full.reflected * 1.01);

    /* Stopped in the middle of the second refinement, at its second report
     * (0.1 s in): many visibility rays per link make it last that long.
     * Wherever the stop falls, the solution is valid. */
    il_hr_desc slow = hd;
    slow.vis_rays = 1024;
    outcome ref = solve(s, slow, never, 2); /* the same with any thread count (hr.h) */
    for (int threads = 1; threads <= 2; threads++) {
        outcome mid = solve(
            s, slow, (watcher){.stop_phase = IL_HR_REFINING, .stop_iterations = 1, .stop_report = 1},
            threads);
        printf("%d thread(s), %s in the second refinement, %.2f s into the solve: reflected "
               "%.5f (converged %.5f), %llu links (converged %llu)\n",
               threads, mid.stats.stopped ? "stopped" : "not stopped (it ended first)",
               mid.w.last_seconds, mid.reflected,
               ref.reflected, (unsigned long long)mid.stats.links,
               (unsigned long long)ref.stats.links);
        CHECK(mid.reflected > 0.0 && mid.reflected <= ref.reflected * 1.01);
        if (mid.stats.stopped)
            CHECK(mid.stats.iterations == 2);
    }

    /* A stop asked after the last iteration ends nothing early. */
    il_hr_desc two = hd;
    two.max_iterations = 2;
    outcome last = solve(s, two, (watcher){.stop_phase = IL_HR_ITERATED, .stop_iterations = 2}, 2);
    CHECK(!last.stats.stopped && last.stats.iterations == 2);

    /* Through il_render: the stopped solution is rendered, and finite. */
    il_film *film = NULL;
    CHECK_OK(il_film_create(16, 16, &film, &g_err), &g_err);
    watcher w = {.stop_phase = IL_HR_ITERATED, .stop_iterations = 1};
    step_watch_begin(&w.sw);
    il_hr_desc rh = hd;
    rh.on_step = on_step;
    rh.on_step_user = &w;
    il_render_desc rd = {.method = IL_METHOD_HR, .threads = 2, .spp = 1, .hr = &rh};
    il_render_stats rs;
    CHECK_OK(il_render(s, film, &rd, &rs, &g_err), &g_err);
    CHECK(rs.hr.stopped && rs.hr.iterations == 1);
    step_watch_check(&w.sw);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    CHECK(image_finite(&img));
    il_image_free(&img);
    il_film_release(film);
    il_scene_release(s);
    return check_report();
}
