/* il_measure_illuminance: light-meter readings at virtual sensors, from the
 * path tracer's paths (il_pt_sensor_irradiance).
 *
 * The samples of every sensor are taken in rounds of blocks; a block's sums
 * are kept apart and added to its sensor's totals in block order after the
 * round, so the readings do not depend on which thread took which block.
 * Blocks are smaller when there are many sensors (a view has one a pixel),
 * so that every round, after which progress is reported and the work may
 * stop, stays about ROUND_SAMPLES long and leaves every sensor with the
 * same number of samples. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/color.h"
#include "core/error.h"
#include "core/sampler.h"
#include "methods/camera_wave.h"
#include "methods/pt/pt.h"
#include "methods/sensor_check.h"

#define BLOCK_SAMPLES 64u           /* most samples of one sensor in one work item */
#define ROUND_SAMPLES (1u << 16)    /* about this many samples between progress calls */
#define MAX_SAMPLES (1u << 30)      /* the Sobol sample index is 32 bits */

typedef struct block_sum {
    double rgb[3];
    double y, yy;                   /* sums of the luminance and its square */
    uint64_t n, bad, rays;
} block_sum;

static il_status check(const il_scene *scene, const il_sensor *sensors, size_t count,
                       const il_illuminance_desc *desc, const il_illuminance *out, il_error *err)
{
    if (!scene || !desc || (count > 0 && (!sensors || !out)))
        return il_fail(err, IL_ERR_INVALID, "illuminance: scene, sensors, options and output are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "illuminance: the scene is not committed (call il_scene_commit)");
    if (desc->samples > MAX_SAMPLES)
        return il_fail(err, IL_ERR_INVALID, "illuminance: %u samples per sensor is more than the %u allowed",
                       desc->samples, MAX_SAMPLES);
    if (desc->max_depth > 1024)
        return il_fail(err, IL_ERR_INVALID, "illuminance: max depth %u is more than 1024", desc->max_depth);
    return il_sensors_check("illuminance", sensors, count, err);
}

/* Adds one sample to a block's sums. */
static void add_sample(block_sum *b, il_vec3 e)
{
    if (!v3_is_finite(e)) {
        b->bad++;
        return;
    }
    double y = il_luminance(e);
    b->rgb[0] += e.x;
    b->rgb[1] += e.y;
    b->rgb[2] += e.z;
    b->y += y;
    b->yy += y * y;
    b->n++;
}

/* A round: nb blocks of every sensor from block `done` on, work item it
 * being block done + it % nb of sensor it / nb. */
typedef struct round_ctx {
    const il_scene *scene;
    const il_illuminance_desc *desc;
    const il_sensor *sensors;
    const il_vec3 *normals;
    uint32_t max_depth, samples, block, done, nb;
    bool prefetch;                  /* il_wave_wants_prefetch, decided once */
} round_ctx;

/* The sample indices [*from, *to) of work item it. */
static void item_samples(const round_ctx *c, int64_t it, uint32_t *from, uint32_t *to)
{
    *from = (c->done + (uint32_t)(it % c->nb)) * c->block;
    *to = c->samples - *from < c->block ? c->samples : *from + c->block;
}

/* The work items [first, last) of a round: their paths traced as one wave
 * (at most IL_PT_WAVE paths), each item's sums formed in sample
 * order. */
static void sample_items(const round_ctx *c, int64_t first, int64_t last, void *scratch,
                         block_sum *part)
{
    il_vec3 p[IL_PT_WAVE] = {{0}}, n[IL_PT_WAVE] = {{0}}, e[IL_PT_WAVE];
    il_sampler smp[IL_PT_WAVE] = {{0}};
    uint32_t count = 0, from, to;
    for (int64_t it = first; it < last; it++) {
        size_t i = (size_t)(it / c->nb);
        item_samples(c, it, &from, &to);
        for (uint32_t k = from; k < to; k++, count++) {
            p[count] = c->sensors[i].position;
            n[count] = c->normals[i];
            il_sampler_start(&smp[count], c->desc->sampler, c->desc->seed, i, k);
        }
    }
    uint64_t rays = 0;
    il_pt_sensor_wave(c->scene, c->max_depth, c->prefetch, scratch, p, n, smp, count, e, &rays);
    count = 0;
    for (int64_t it = first; it < last; it++) {
        block_sum *b = &part[it];
        memset(b, 0, sizeof *b);
        item_samples(c, it, &from, &to);
        for (uint32_t k = from; k < to; k++)
            add_sample(b, e[count++]);
    }
    part[first].rays = rays; /* the wave's rays, counted once */
}

static void add_sum(block_sum *to, const block_sum *b)
{
    for (int c = 0; c < 3; c++)
        to->rgb[c] += b->rgb[c];
    to->y += b->y;
    to->yy += b->yy;
    to->n += b->n;
    to->bad += b->bad;
    to->rays += b->rays;
}

static il_illuminance reading(const block_sum *t)
{
    il_illuminance r = {0};
    if (t->n == 0)
        return r;
    double n = (double)t->n, mean = t->y / n;
    r.irradiance = (il_vec3){(float)(t->rgb[0] / n), (float)(t->rgb[1] / n), (float)(t->rgb[2] / n)};
    r.lux = (float)(IL_LUMENS_PER_WATT * mean);
    if (t->n > 1) {
        double var = (t->yy - n * mean * mean) / (n - 1.0); /* unbiased sample variance */
        r.lux_error = (float)(IL_LUMENS_PER_WATT * sqrt(fmax(var, 0.0) / n));
    }
    return r;
}

il_status il_measure_illuminance(const il_scene *scene, const il_sensor *sensors, size_t count,
                                 const il_illuminance_desc *desc, il_illuminance *out,
                                 il_illuminance_stats *stats, il_error *err)
{
    if (stats)
        memset(stats, 0, sizeof *stats);
    il_status st = check(scene, sensors, count, desc, out, err);
    if (st != IL_OK)
        return st;
    uint32_t samples = desc->samples ? desc->samples : 1024u;
    uint32_t max_depth = desc->max_depth ? desc->max_depth : 8u;
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    /* The block size and the blocks per sensor in a round depend on the
     * sensor and sample counts only, never on the threads. */
    uint64_t per_sensor = ROUND_SAMPLES / (count ? count : 1);
    uint32_t block = per_sensor < 1 ? 1u : (per_sensor > BLOCK_SAMPLES ? BLOCK_SAMPLES : (uint32_t)per_sensor);
    uint32_t blocks = (uint32_t)(((uint64_t)samples + block - 1) / block);
    uint64_t per_round = per_sensor / block;
    uint32_t round_blocks = per_round < 1 ? 1u : (per_round > blocks ? blocks : (uint32_t)per_round);

    il_vec3 *normals = malloc((count ? count : 1) * sizeof *normals);
    block_sum *total = calloc(count ? count : 1, sizeof *total);
    block_sum *part = malloc((count ? count : 1) * round_blocks * sizeof *part);
    size_t stride = (il_pt_wavefront_scratch_bytes() + 63) / 64 * 64;
    unsigned char *scratch = aligned_alloc(64, (size_t)threads * stride);
    if (!normals || !total || !part || !scratch) {
        free(normals), free(total), free(part), free(scratch);
        return il_fail(err, IL_ERR_MEMORY, "illuminance: out of memory for %zu sensors", count);
    }
    for (size_t i = 0; i < count; i++)
        normals[i] = v3_normalize(sensors[i].normal);

    /* Items in waves of as many whole blocks as a wave holds. */
    int64_t per_wave = IL_PT_WAVE / block;
    round_ctx c = {scene, desc, sensors, normals, max_depth, samples, block, 0, 0,
                   il_wave_wants_prefetch(scene)};
    double t0 = omp_get_wtime();
    uint32_t done = 0;                  /* blocks of every sensor added so far */
    while (done < blocks && count > 0) {
        uint32_t nb = blocks - done < round_blocks ? blocks - done : round_blocks;
        int64_t items = (int64_t)count * nb;
        int64_t waves = (items + per_wave - 1) / per_wave;
        c.done = done;
        c.nb = nb;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
        for (int64_t wv = 0; wv < waves; wv++) {
            int64_t last = (wv + 1) * per_wave < items ? (wv + 1) * per_wave : items;
            sample_items(&c, wv * per_wave, last, scratch + (size_t)omp_get_thread_num() * stride,
                         part);
        }
        for (int64_t it = 0; it < items; it++)
            add_sum(&total[it / nb], &part[it]);
        done += nb;
        if (desc->progress && done < blocks &&
            !desc->progress((double)done / blocks, omp_get_wtime() - t0, desc->progress_user))
            break;
    }
    uint32_t taken = done >= blocks ? samples : done * block;
    uint64_t rays = 0, bad = 0;
    for (size_t i = 0; i < count; i++) {
        out[i] = reading(&total[i]);
        rays += total[i].rays;
        bad += total[i].bad;
    }
    if (stats) {
        stats->samples = count ? taken : 0;
        stats->rays = rays;
        stats->nonfinite_samples = bad;
        stats->seconds = omp_get_wtime() - t0;
    }
    free(normals), free(total), free(part), free(scratch);
    return IL_OK;
}
