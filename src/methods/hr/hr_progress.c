/* il_hr_desc.on_step during a solve (hr.h, illum.h): progress reports from
 * the calling thread and the stop request the other threads read.
 *
 * Reports come from thread 0 of the solve's parallel regions, which is the
 * thread that called il_hr_solve, so the callback never runs on a worker.
 * Between reports the cost is a thread-number test, and a clock read every
 * 16th call. */
#include <omp.h>

#include "methods/hr/hr.h"

/* Seconds between two reports of the same phase. */
#define REPORT_INTERVAL 0.1

static void report(const il_hr_solver *s, double energy_change, double now)
{
    il_hr_watch *w = s->watch;
    il_hr_progress p = {
        .phase = w->phase,
        .iterations = w->iterations,
        .roots_done = atomic_load_explicit(&w->roots_done, memory_order_relaxed),
        .num_roots = s->num_roots,
        .energy_change = energy_change,
        .seconds = now - w->t0,
    };
    w->next_report = now + REPORT_INTERVAL;
    if (!s->set.on_step(&p, s->set.on_step_user))
        atomic_store_explicit(&w->stop, true, memory_order_relaxed);
}

void il_hr_watch_start(il_hr_solver *s, il_hr_watch *w)
{
    atomic_init(&w->stop, false);
    atomic_init(&w->roots_done, 0u);
    w->phase = IL_HR_LINKING;
    w->iterations = 0;
    w->polls = 0;
    w->t0 = omp_get_wtime();
    w->next_report = w->t0;
    s->watch = w;
}

void il_hr_watch_phase(const il_hr_solver *s, il_hr_phase phase, uint32_t iterations,
                       double energy_change)
{
    il_hr_watch *w = s->watch;
    if (!w)
        return;
    w->phase = phase;
    w->iterations = iterations;
    atomic_store_explicit(&w->roots_done, 0u, memory_order_relaxed);
    if (s->set.on_step && !il_hr_stopping(s))
        report(s, energy_change, omp_get_wtime());
}

void il_hr_watch_root_done(const il_hr_solver *s)
{
    if (s->watch)
        atomic_fetch_add_explicit(&s->watch->roots_done, 1u, memory_order_relaxed);
}

void il_hr_watch_poll(const il_hr_solver *s)
{
    il_hr_watch *w = s->watch;
    if (!w || !s->set.on_step || omp_get_thread_num() != 0 || il_hr_stopping(s))
        return;
    if ((++w->polls & 15u) != 0) /* the clock every 16th call (a link costs microseconds) */
        return;
    double now = omp_get_wtime();
    if (now >= w->next_report)
        report(s, 0.0, now);
}
