/* il_photon_desc.on_step (illum.h, il_photon_step_fn): photon mapping's
 * set-up reports its progress on the calling thread and stops when asked.
 *   - reports come in order: tracing with the photons done growing to the
 *     total, then the irradiance points likewise;
 *   - stopped while tracing: il_photon_stats.emitted is the photons traced,
 *     and the film is bit for bit the one of a render asking for that many
 *     photons without precomputed irradiance (the same prefix of photon
 *     indices, each carrying the lights' power over their number);
 *   - stopped while precomputing irradiance: every photon is kept and the
 *     film is the one without precomputed irradiance;
 *   - a report that never asks to stop leaves the film as without on_step. */
#include "mesh_compare.h"
#include "step_watch.h"

#define W 32
#define H 32

typedef struct watcher {
    il_photon_phase stop_phase;
    uint64_t stop_at;              /* stop at the first report of stop_phase with done >= this */
    step_watch sw;
    uint32_t irradiance_calls;
    il_photon_phase last_phase;
    uint64_t last_done, last_total, stopped_at;
} watcher;

static bool on_step(const il_photon_progress *p, void *user)
{
    watcher *w = user;
    bool later = w->sw.calls == 0 || p->phase > w->last_phase ||
                 (p->phase == w->last_phase && p->done >= w->last_done);
    step_watch_report(&w->sw, p->done <= p->total && later);
    w->irradiance_calls += p->phase == IL_PHOTON_IRRADIANCE;
    w->last_phase = p->phase;
    w->last_done = p->done;
    w->last_total = p->total;
    if (p->phase == w->stop_phase && p->done >= w->stop_at) {
        w->stopped_at = p->done;
        return false;
    }
    return true;
}

static il_image render(const il_scene *s, il_photon_desc pd, watcher *w, il_render_stats *st)
{
    if (w) {
        pd.on_step = on_step;
        pd.on_step_user = w;
    }
    il_render_desc rd = {.method = IL_METHOD_PHOTON, .spp = 2, .threads = 2, .seed = 3,
                         .photon = &pd};
    return step_watch_render(s, W, H, &rd, w ? &w->sw : NULL, st);
}

int main(void)
{
    il_scene *s = load_committed("cornell-spheres");
    if (!s)
        return check_report();
    const il_photon_desc pd = {.photons = 400000};
    il_photon_desc no_irr = pd;
    no_irr.no_precomputed_irradiance = 1;

    /* Watched to the end: the same film, every phase reported. */
    il_render_stats st;
    il_image plain = render(s, pd, NULL, &st);
    watcher all = {.stop_phase = (il_photon_phase)99};
    il_image watched = render(s, pd, &all, &st);
    CHECK(images_identical(&plain, &watched));
    CHECK(!st.photon.stopped && st.photon.emitted == pd.photons);
    CHECK(all.sw.calls >= 4 && all.irradiance_calls >= 1);
    CHECK(all.last_phase == IL_PHOTON_IRRADIANCE && all.last_total > 0);
    printf("%u reports, %u of them for the irradiance\n", all.sw.calls, all.irradiance_calls);

    /* Stopped while tracing, part-way. */
    watcher tracing = {.stop_phase = IL_PHOTON_TRACING, .stop_at = pd.photons / 3};
    il_image stopped = render(s, pd, &tracing, &st);
    printf("stopped tracing at %llu of %llu photons\n", (unsigned long long)tracing.stopped_at,
           (unsigned long long)pd.photons);
    CHECK(st.photon.stopped);
    CHECK(st.photon.emitted == tracing.stopped_at);
    CHECK(st.photon.emitted >= pd.photons / 3 && st.photon.emitted < pd.photons);
    CHECK(tracing.irradiance_calls == 0);
    il_photon_desc fewer = no_irr;
    fewer.photons = st.photon.emitted;
    il_image asked = render(s, fewer, NULL, &st);
    CHECK(images_identical(&stopped, &asked));
    CHECK(image_mean(&stopped, 1) > 0.0);

    /* Stopped as the irradiance starts: all photons, full estimates. */
    watcher irradiance = {.stop_phase = IL_PHOTON_IRRADIANCE};
    il_image no_table = render(s, pd, &irradiance, &st);
    CHECK(st.photon.stopped && st.photon.emitted == pd.photons);
    il_image full = render(s, no_irr, NULL, &st);
    CHECK(images_identical(&no_table, &full));

    il_image_free(&plain);
    il_image_free(&watched);
    il_image_free(&stopped);
    il_image_free(&asked);
    il_image_free(&no_table);
    il_image_free(&full);
    il_scene_release(s);
    return check_report();
}
