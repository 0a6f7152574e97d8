/* The accumulation film: per pixel the weighted sum of radiance samples and
 * the sum of their weights, both in double so that millions of samples per
 * pixel do not lose precision (a float sum stops growing once a sample is
 * below 2^-24 of it).  il_film_resolve divides them (pbrt-v4, section 5.4.3:
 * the weighted mean of the filter-weighted samples). */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "illum/illum.h"

#define IL_FILM_MAX_SIDE 65536u

struct il_film {
    uint32_t width, height;
    double *sums; /* 4 per pixel: sum w*r, sum w*g, sum w*b, sum w */
};

il_status il_film_create(uint32_t width, uint32_t height, il_film **out, il_error *err)
{
    if (!out)
        return il_fail(err, IL_ERR_INVALID, "il_film_create: out is NULL");
    *out = NULL;
    if (width == 0 || height == 0 || width > IL_FILM_MAX_SIDE || height > IL_FILM_MAX_SIDE)
        return il_fail(err, IL_ERR_INVALID, "film size %ux%u is out of range (1..%u per side)",
                       width, height, IL_FILM_MAX_SIDE);
    il_film *film = il_calloc(1, sizeof *film, err);
    if (!film)
        return IL_ERR_MEMORY;
    film->sums = il_calloc((size_t)width * height * 4, sizeof(double), err);
    if (!film->sums) {
        free(film);
        return IL_ERR_MEMORY;
    }
    film->width = width;
    film->height = height;
    *out = film;
    return IL_OK;
}

uint32_t il_film_width(const il_film *film) { return film ? film->width : 0; }
uint32_t il_film_height(const il_film *film) { return film ? film->height : 0; }
double *il_film_data(il_film *film) { return film ? film->sums : NULL; }

void il_film_clear(il_film *film)
{
    if (film)
        memset(film->sums, 0, (size_t)film->width * film->height * 4 * sizeof(double));
}

/* Called from many threads, each on its own pixels: no locking.  Samples
 * outside the film are ignored.  Values are stored as given (a NaN sample
 * makes its pixel NaN, which il_image_compare then reports). */
void il_film_add_sample(il_film *film, uint32_t x, uint32_t y, il_vec3 radiance, float weight)
{
    if (!film || x >= film->width || y >= film->height)
        return;
    double *s = film->sums + ((size_t)y * film->width + x) * 4;
    double w = weight;
    s[0] += w * radiance.x;
    s[1] += w * radiance.y;
    s[2] += w * radiance.z;
    s[3] += w;
}

il_status il_film_resolve(const il_film *film, il_image *out, il_error *err)
{
    if (!film)
        return il_fail(err, IL_ERR_INVALID, "il_film_resolve: film is NULL");
    il_status st = il_image_alloc(out, film->width, film->height, err);
    if (st != IL_OK)
        return st;
    size_t n = (size_t)film->width * film->height;
    for (size_t i = 0; i < n; i++) {
        const double *s = film->sums + i * 4;
        if (s[3] != 0.0) {
            double inv = 1.0 / s[3];
            out->rgb[i * 3 + 0] = (float)(s[0] * inv);
            out->rgb[i * 3 + 1] = (float)(s[1] * inv);
            out->rgb[i * 3 + 2] = (float)(s[2] * inv);
        } /* else stays 0 from il_image_alloc's calloc */
    }
    return IL_OK;
}

void il_film_release(il_film *film)
{
    if (!film)
        return;
    free(film->sums);
    free(film);
}
