/* What the tests of the set-up callbacks (il_hr_desc.on_step,
 * il_photon_desc.on_step, il_linespace_desc.on_step) check of every report:
 * it comes on the thread that started the render, and in order. */
#ifndef IL_TESTS_STEP_WATCH_H
#define IL_TESTS_STEP_WATCH_H

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>

#include "check.h"
#include "pt_scenes.h"

typedef struct step_watch {
    pthread_t caller;
    bool on_caller, in_order;
    uint32_t calls;                /* reports so far */
} step_watch;

/* Before the render, on its calling thread. */
static inline void step_watch_begin(step_watch *w)
{
    w->caller = pthread_self();
    w->on_caller = w->in_order = true;
    w->calls = 0;
}

/* In the callback: one report, in order or not after the previous one. */
static inline void step_watch_report(step_watch *w, bool in_order)
{
    if (!pthread_equal(pthread_self(), w->caller))
        w->on_caller = false;
    if (!in_order)
        w->in_order = false;
    w->calls++;
}

/* After the render. */
static inline void step_watch_check(const step_watch *w)
{
    CHECK(w->in_order);
    CHECK(w->on_caller);
}

/* A render of w x h with rd whose set-up callback (installed by the caller)
 * reports to sw, when sw is not NULL: the image, checked finite, and the
 * reports checked after it. */
static inline il_image step_watch_render(const il_scene *s, uint32_t w, uint32_t h,
                                         const il_render_desc *rd, step_watch *sw,
                                         il_render_stats *st)
{
    if (sw)
        step_watch_begin(sw);
    il_image img = render_desc_image(s, w, h, rd, st);
    CHECK(image_finite(&img));
    if (sw)
        step_watch_check(sw);
    return img;
}

#endif
