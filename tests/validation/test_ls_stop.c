/* il_linespace_desc.on_step (illum.h, il_linespace_step_fn): the light
 * injection reports its progress on the calling thread and stops when asked.
 *   - reports come in order, the paths injected growing to the total;
 *   - watched to the end, the film is the one without on_step, bit for bit;
 *   - stopped part-way, il_linespace_stats.inject_rays is the paths injected
 *     and the film is bit for bit the one of asking for that many (the same
 *     first path indices, each entry divided by their number);
 *   - stopped at the first report, nothing is injected and the render still
 *     completes (the Linespace reads as no light; lookups that trace on
 *     still find it). */
#include "mesh_compare.h"
#include "step_watch.h"

#define W 32
#define H 32

typedef struct watcher {
    uint64_t stop_at;              /* stop at the first report with injected >= this */
    step_watch sw;
    uint64_t last, stopped_at;
} watcher;

static bool on_step(const il_linespace_progress *p, void *user)
{
    watcher *w = user;
    step_watch_report(&w->sw, p->injected <= p->total && (w->sw.calls == 0 || p->injected >= w->last));
    w->last = p->injected;
    if (p->injected >= w->stop_at) {
        w->stopped_at = p->injected;
        return false;
    }
    return true;
}

static il_image render(const il_scene *s, il_linespace_desc ld, watcher *w, il_render_stats *st)
{
    if (w) {
        ld.on_step = on_step;
        ld.on_step_user = w;
    }
    il_render_desc rd = {.method = IL_METHOD_LINESPACE, .spp = 2, .max_depth = 4, .threads = 2,
                         .seed = 3, .linespace = &ld};
    return step_watch_render(s, W, H, &rd, w ? &w->sw : NULL, st);
}

int main(void)
{
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    const il_linespace_desc ld = {.grid = 4, .n = 2, .inject_rays = 300000};
    il_render_stats st;

    il_image plain = render(s, ld, NULL, &st);
    watcher all = {.stop_at = UINT64_MAX};
    il_image watched = render(s, ld, &all, &st);
    CHECK(images_identical(&plain, &watched));
    CHECK(!st.linespace.stopped && st.linespace.inject_rays == ld.inject_rays);
    CHECK(all.sw.calls >= 2);
    printf("%u reports for %llu paths\n", all.sw.calls, (unsigned long long)ld.inject_rays);

    watcher part = {.stop_at = ld.inject_rays / 3};
    il_image stopped = render(s, ld, &part, &st);
    printf("stopped at %llu of %llu paths\n", (unsigned long long)part.stopped_at,
           (unsigned long long)ld.inject_rays);
    CHECK(st.linespace.stopped && st.linespace.inject_rays == part.stopped_at);
    CHECK(part.stopped_at >= ld.inject_rays / 3 && part.stopped_at < ld.inject_rays);
    il_linespace_desc fewer = ld;
    fewer.inject_rays = part.stopped_at;
    il_image asked = render(s, fewer, NULL, &st);
    CHECK(images_identical(&stopped, &asked));
    CHECK(image_mean(&stopped, 1) > 0.0);

    watcher first = {.stop_at = 0};
    il_image none = render(s, ld, &first, &st);
    CHECK(st.linespace.stopped && st.linespace.inject_rays == 0 && first.sw.calls == 1);

    il_image_free(&plain);
    il_image_free(&watched);
    il_image_free(&stopped);
    il_image_free(&asked);
    il_image_free(&none);
    il_scene_release(s);
    return check_report();
}
