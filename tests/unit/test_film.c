/* The accumulation film: weighted means, precision over many samples,
 * lock-free use from threads on distinct pixels. */
#include <math.h>

#include "check.h"
#include "illum/illum.h"

static void test_film(void)
{
    il_error err = {0};
    il_film *film = NULL;
    CHECK(il_film_create(0, 4, &film, &err) == IL_ERR_INVALID && film == NULL);
    CHECK(il_film_create(70000, 4, &film, &err) == IL_ERR_INVALID);
    CHECK_OK(il_film_create(4, 3, &film, &err), &err);
    if (!film)
        return;
    CHECK(il_film_width(film) == 4 && il_film_height(film) == 3);

    /* Weighted mean: (1*(1,2,3) + 3*(3,2,1)) / 4 = (2.5, 2, 1.5). */
    il_film_add_sample(film, 1, 2, (il_vec3){1, 2, 3}, 1.0f);
    il_film_add_sample(film, 1, 2, (il_vec3){3, 2, 1}, 3.0f);
    il_film_add_sample(film, 4, 0, (il_vec3){9, 9, 9}, 1.0f); /* outside: ignored */
    il_film_add_sample(film, 0, 3, (il_vec3){9, 9, 9}, 1.0f); /* outside: ignored */
    /* Many samples: a double sum keeps the small ones.  (1e8 + 1e4*1) / 10001
     * = 1e4 exactly; a float sum would give 1e8/10001 = 9999.0. */
    il_film_add_sample(film, 3, 0, (il_vec3){1e8f, 0, 0}, 1.0f);
    for (int i = 0; i < 10000; i++)
        il_film_add_sample(film, 3, 0, (il_vec3){1, 0, 0}, 1.0f);

    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    CHECK(img.width == 4 && img.height == 3);
    const float *p = img.rgb + (2 * 4 + 1) * 3;
    CHECK_NEAR(p[0], 2.5, 1e-6);
    CHECK_NEAR(p[1], 2.0, 1e-6);
    CHECK_NEAR(p[2], 1.5, 1e-6);
    CHECK_REL(img.rgb[3 * 3], 1e4, 1e-7);
    /* Pixels without weight resolve to 0. */
    int zeros = 0;
    for (int i = 0; i < 12; i++)
        if (i != 2 * 4 + 1 && i != 3)
            zeros += img.rgb[i * 3] == 0 && img.rgb[i * 3 + 1] == 0 && img.rgb[i * 3 + 2] == 0;
    CHECK(zeros == 10);
    il_image_free(&img);

    /* Clear empties it. */
    il_film_clear(film);
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    double sum = 0;
    for (int i = 0; i < 36; i++)
        sum += fabs(img.rgb[i]);
    CHECK(sum == 0.0);
    il_image_free(&img);
    il_film_release(film);
}

/* Threads adding samples to distinct pixels need no lock: the result equals
 * the serial one exactly. */
static void test_film_threads(void)
{
    il_error err = {0};
    il_film *film = NULL;
    CHECK_OK(il_film_create(64, 64, &film, &err), &err);
    if (!film)
        return;
#pragma omp parallel for schedule(dynamic, 1)
    for (int y = 0; y < 64; y++)
        for (int s = 0; s < 16; s++)
            for (int x = 0; x < 64; x++)
                il_film_add_sample(film, (uint32_t)x, (uint32_t)y,
                                   (il_vec3){(float)x, (float)y, (float)s}, 0.5f);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    int bad = 0;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            const float *p = img.rgb + ((size_t)y * 64 + x) * 3;
            bad += p[0] != (float)x || p[1] != (float)y || p[2] != 7.5f;
        }
    CHECK(bad == 0);
    il_image_free(&img);
    il_film_release(film);
}

int main(void)
{
    test_film();
    test_film_threads();
    return check_report();
}
