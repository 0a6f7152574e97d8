/* SPPM converges to the path tracer: on the built-in Cornell box its RMS
 * difference from a 2048-spp path-traced image falls as passes are added
 * (read from the film the progress callback sees after each pass), and
 * after 64 passes each wall's mean radiance is within 5% of the path
 * tracer's.  The progress report's radius (the mean per-pixel search
 * radius) starts at most at the initial radius and shrinks pass by pass
 * (Hachisuka & Jensen 2009, eq. 8-10). */
#include "mesh_compare.h"

#define W 32
#define H 32

typedef struct watch {
    const il_image *ref;
    double rms[65];
    double radius[65];
} watch;

static bool on_pass(const il_render_progress *p, void *user)
{
    watch *w = user;
    il_image img = {0};
    if (p->passes_done < 65 && il_film_resolve(p->film, &img, NULL) == IL_OK)
        w->rms[p->passes_done] = rel_rms(&img, w->ref);
    if (p->passes_done < 65)
        w->radius[p->passes_done] = p->radius;
    il_image_free(&img);
    return true;
}

int main(void)
{
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();

    il_render_desc pt = {.method = IL_METHOD_PT, .spp = 2048, .max_depth = 64, .threads = 2, .seed = 9};
    il_image ref = render_desc_image(s, W, H, &pt, NULL);

    watch w = {.ref = &ref};
    il_photon_desc pd = {.photons = 50000};
    il_render_desc rd = {.method = IL_METHOD_SPPM, .spp = 64, .max_depth = 64, .threads = 2,
                         .seed = 9, .photon = &pd, .progress = on_pass, .progress_user = &w};
    il_render_stats st;
    il_image img = render_desc_image(s, W, H, &rd, &st);
    CHECK(st.spp == 64 && st.photon.passes == 64 && st.photon.emitted == 64u * 50000u);
    for (int k = 1; k <= 64; k *= 2)
        printf("pass %2d: relative RMS difference from the path tracer %.4f, mean radius %.5f m\n", k,
               w.rms[k], w.radius[k]);
    CHECK(w.radius[1] > 0.0 && w.radius[1] <= 0.01);
    for (int k = 2; k <= 64; k++)
        CHECK(w.radius[k] <= w.radius[k - 1] * 1.02); /* the pixels averaged vary a little */
    CHECK(w.radius[64] < 0.8 * w.radius[1]);
    CHECK(w.rms[4] < w.rms[1]);
    CHECK(w.rms[16] < w.rms[4]);
    CHECK(w.rms[64] < w.rms[16]);
    CHECK(w.rms[64] < 0.5 * w.rms[1]);
    CHECK(compare_mesh_means(s, &img, &ref, 0.05, 0.0, "sppm", "pt") >= 6);
    il_image_free(&img);
    il_image_free(&ref);
    il_scene_release(s);
    return check_report();
}
