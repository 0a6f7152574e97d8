/* il_photon_desc.on_photons, the photon positions for display (the
 * viewer's photon points), on the Cornell box: photon mapping reports the
 * global map (which 0, as many photons as stats.stored_global) and the
 * caustic map (which 1, stored_caustic), SPPM every pass (which 2, their sum
 * is stats.stored); every position lies in the scene's bounds; the callback
 * changes nothing in the image. */
#include <string.h>

#include "check.h"
#include "illum/illum.h"

static il_error g_err;

typedef struct seen {
    uint32_t calls[3];
    uint64_t count[3];
    uint64_t outside;
    il_vec3 lo, hi;
} seen;

static void on_photons(const float *xyz, size_t count, int which, void *user)
{
    seen *s = user;
    if (which < 0 || which > 2)
        return;
    s->calls[which]++;
    s->count[which] += count;
    const float eps = 1e-4f;
    for (size_t i = 0; i < count; i++) {
        const float *p = xyz + 3 * i;
        if (p[0] < s->lo.x - eps || p[1] < s->lo.y - eps || p[2] < s->lo.z - eps ||
            p[0] > s->hi.x + eps || p[1] > s->hi.y + eps || p[2] > s->hi.z + eps)
            s->outside++;
    }
}

static il_image render(const il_scene *sc, il_method m, il_photon_desc *pd, il_render_stats *rs)
{
    il_film *film = NULL;
    il_image img = {0};
    CHECK_OK(il_film_create(32, 32, &film, &g_err), &g_err);
    il_render_desc d = {.method = m, .spp = 2, .seed = 4, .threads = 2, .photon = pd};
    CHECK_OK(il_render(sc, film, &d, rs, &g_err), &g_err);
    CHECK_OK(il_film_resolve(film, &img, &g_err), &g_err);
    il_film_release(film);
    return img;
}

static bool same_image(const il_image *a, const il_image *b)
{
    return a->rgb && b->rgb && a->width == b->width && a->height == b->height &&
           !memcmp(a->rgb, b->rgb, sizeof(float) * 3 * a->width * a->height);
}

int main(void)
{
    il_scene *sc = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &sc, &g_err), &g_err);
    if (!sc)
        return check_report();
    CHECK_OK(il_scene_commit(sc, &g_err), &g_err);
    il_scene_info info;
    il_scene_get_info(sc, &info);

    const il_method methods[2] = {IL_METHOD_PHOTON, IL_METHOD_SPPM};
    for (int k = 0; k < 2; k++) {
        seen s = {.lo = info.bounds_min, .hi = info.bounds_max};
        il_photon_desc plain = {.photons = 20000};
        il_photon_desc watched = plain;
        watched.on_photons = on_photons;
        watched.on_photons_user = &s;
        il_render_stats r0, r1;
        il_image a = render(sc, methods[k], &plain, &r0);
        il_image b = render(sc, methods[k], &watched, &r1);
        printf("%s: calls %u %u %u, photons %llu %llu %llu, outside %llu\n",
               k ? "sppm" : "photon", s.calls[0], s.calls[1], s.calls[2],
               (unsigned long long)s.count[0], (unsigned long long)s.count[1],
               (unsigned long long)s.count[2], (unsigned long long)s.outside);
        if (k == 0) {
            CHECK(s.calls[0] == 1 && s.calls[1] == 1 && s.calls[2] == 0);
            CHECK(s.count[0] == r1.photon.stored_global);
            CHECK(s.count[1] == r1.photon.stored_caustic);
            CHECK(s.count[0] > 1000);
        } else {
            CHECK(s.calls[0] == 0 && s.calls[1] == 0 && s.calls[2] == 2);
            CHECK(s.count[2] == r1.photon.stored);
            CHECK(s.count[2] > 1000);
        }
        CHECK(s.outside == 0);
        CHECK(same_image(&a, &b));
        il_image_free(&a);
        il_image_free(&b);
    }
    il_scene_release(sc);
    return check_report();
}
