/* il_render_region and il_film_data (the work unit of the distributed render,
 * docs/distributed.md): regions rendered apart into cleared films and added
 * give il_render's film bit for bit; bad regions and options are refused. */
#include <string.h>

#include "check.h"
#include "illum/illum.h"

enum { W = 37, H = 21 };

int main(void)
{
    il_error err = {0};
    il_scene *scene = NULL;
    CHECK_OK(il_scene_load("cornell", NULL, &scene, &err), &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    il_film *ref = NULL, *a = NULL, *b = NULL;
    CHECK_OK(il_film_create(W, H, &ref, &err), &err);
    CHECK_OK(il_film_create(W, H, &a, &err), &err);
    CHECK_OK(il_film_create(W, H, &b, &err), &err);
    if (!scene || !ref || !a || !b)
        return check_report();

    il_render_desc d = {.method = IL_METHOD_PT, .spp = 5, .seed = 9, .threads = 2,
                        .filter = IL_FILTER_GAUSSIAN};
    il_render_stats rs;
    CHECK_OK(il_render(scene, ref, &d, &rs, &err), &err);

    /* Film a: two regions, one of them rendered in two calls of disjoint
     * rectangles; film b: the rest.  Irregular cuts, not on the 16-pixel grid. */
    il_render_rect r1 = {0, 0, 23, 21}, r2a = {23, 0, 37, 9}, r2b = {23, 9, 37, 21};
    il_render_stats s1, s2, s3;
    d.threads = 1;
    CHECK_OK(il_render_region(scene, a, &d, &r1, &s1, &err), &err);
    d.threads = 3;
    CHECK_OK(il_render_region(scene, b, &d, &r2a, &s2, &err), &err);
    CHECK_OK(il_render_region(scene, b, &d, &r2b, &s3, &err), &err);
    CHECK(s1.spp == 5 && s2.spp == 5);
    CHECK(s1.rays + s2.rays + s3.rays == rs.rays);

    /* b holds nothing inside r1: the sum is a plain copy there. */
    double *pa = il_film_data(a), *pb = il_film_data(b), *pr = il_film_data(ref);
    CHECK(pa && pb && pr);
    CHECK(pb[0] == 0.0 && pa[4 * (W - 1)] == 0.0);
    size_t n = (size_t)W * H * 4, differ = 0;
    for (size_t i = 0; i < n; i++) {
        double sum = pa[i] + pb[i];
        if (memcmp(&sum, &pr[i], sizeof sum) != 0)
            differ++;
    }
    CHECK(differ == 0);
    /* Not a tautology: another seed changes the bits. */
    il_film_clear(a);
    d.seed = 10;
    CHECK_OK(il_render_region(scene, a, &d, &r1, NULL, &err), &err);
    size_t changed = 0;
    for (size_t i = 0; i < n; i++)
        changed += memcmp(&pa[i], &pr[i], sizeof pa[i]) != 0;
    CHECK(changed > n / 8);

    /* Bad input. */
    il_render_rect empty = {5, 5, 5, 9}, outside = {0, 0, W + 1, H};
    CHECK(il_render_region(scene, a, &d, &empty, NULL, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "outside") != NULL);
    CHECK(il_render_region(scene, a, &d, &outside, NULL, &err) == IL_ERR_INVALID);
    CHECK(il_render_region(scene, a, &d, NULL, NULL, &err) == IL_ERR_INVALID);
    il_render_desc timed = d;
    timed.time_limit = 1.0;
    CHECK(il_render_region(scene, a, &timed, &r1, NULL, &err) == IL_ERR_INVALID);
    il_render_desc rad = d;
    rad.method = IL_METHOD_RADIOSITY;
    CHECK(il_render_region(scene, a, &rad, &r1, NULL, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "path tracer") != NULL);
    CHECK(il_film_data(NULL) == NULL);

    il_film_release(ref);
    il_film_release(a);
    il_film_release(b);
    il_scene_release(scene);
    return check_report();
}
