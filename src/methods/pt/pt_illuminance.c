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
#include "methods/pt/pt.h"
#include "scene/camera.h"

#define BLOCK_SAMPLES 64u           /* most samples of one sensor in one work item */
#define ROUND_SAMPLES (1u << 16)    /* about this many samples between progress calls */
#define MAX_SAMPLES (1u << 30)      /* the Sobol sample index is 32 bits */
#define LUMENS_PER_WATT 683.0       /* the luminous efficacy the loaders use too (docs/scene-format.md) */

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
    for (size_t i = 0; i < count; i++) {
        il_vec3 p = sensors[i].position, n = sensors[i].normal;
        if (!v3_is_finite(p) || !v3_is_finite(n))
            return il_fail(err, IL_ERR_INVALID, "illuminance: sensor %zu has a NaN or infinite coordinate", i);
        if (!(v3_length(n) > 0.0f))
            return il_fail(err, IL_ERR_INVALID, "illuminance: sensor %zu has a zero normal", i);
    }
    return IL_OK;
}

static void sample_block(const il_scene *scene, const il_illuminance_desc *desc, uint32_t max_depth,
                         il_vec3 p, il_vec3 n, uint64_t sensor, uint32_t first, uint32_t count,
                         block_sum *out)
{
    memset(out, 0, sizeof *out);
    for (uint32_t k = first; k < first + count; k++) {
        il_sampler smp;
        il_sampler_start(&smp, desc->sampler, desc->seed, sensor, k);
        il_vec3 e = il_pt_sensor_irradiance(scene, p, n, &smp, max_depth, &out->rays);
        if (!v3_is_finite(e)) {
            out->bad++;
            continue;
        }
        double y = il_luminance(e);
        out->rgb[0] += e.x;
        out->rgb[1] += e.y;
        out->rgb[2] += e.z;
        out->y += y;
        out->yy += y * y;
        out->n++;
    }
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
    r.lux = (float)(LUMENS_PER_WATT * mean);
    if (t->n > 1) {
        double var = (t->yy - n * mean * mean) / (n - 1.0); /* unbiased sample variance */
        r.lux_error = (float)(LUMENS_PER_WATT * sqrt(fmax(var, 0.0) / n));
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
    if (!normals || !total || !part) {
        free(normals), free(total), free(part);
        return il_fail(err, IL_ERR_MEMORY, "illuminance: out of memory for %zu sensors", count);
    }
    for (size_t i = 0; i < count; i++)
        normals[i] = v3_normalize(sensors[i].normal);

    double t0 = omp_get_wtime();
    uint32_t done = 0;                  /* blocks of every sensor added so far */
    while (done < blocks && count > 0) {
        uint32_t nb = blocks - done < round_blocks ? blocks - done : round_blocks;
        int64_t items = (int64_t)count * nb;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
        for (int64_t it = 0; it < items; it++) {
            size_t i = (size_t)(it / nb);
            uint32_t b = done + (uint32_t)(it % nb);
            uint32_t first = b * block;
            uint32_t n = samples - first < block ? samples - first : block;
            sample_block(scene, desc, max_depth, sensors[i].position, normals[i], i, first, n,
                         &part[it]);
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
    free(normals), free(total), free(part);
    return IL_OK;
}

il_status il_camera_sensors(const il_scene *scene, uint32_t width, uint32_t height,
                            il_sensor *sensors, bool *seen, il_error *err)
{
    if (!scene || !sensors || !seen || width == 0 || height == 0)
        return il_fail(err, IL_ERR_INVALID, "camera sensors: scene, a non-empty size and outputs are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "camera sensors: the scene is not committed (call il_scene_commit)");
    il_camera_desc d;
    if (!il_scene_get_camera(scene, &d))
        return il_fail(err, IL_ERR_INVALID, "camera sensors: the scene has no camera");
    il_camera cam;
    il_camera_init(&cam, &d, width, height);
#pragma omp parallel for schedule(dynamic, 4)
    for (int64_t y = 0; y < (int64_t)height; y++) {
        for (uint32_t x = 0; x < width; x++) {
            size_t i = (size_t)y * width + x;
            il_ray ray = {.org = cam.position, .tmin = 0.0f,
                          .dir = il_camera_ray_dir(&cam, (float)x + 0.5f, (float)y + 0.5f),
                          .tmax = INFINITY};
            il_hit hit;
            seen[i] = il_trace_closest(scene->tracer, &ray, &hit);
            sensors[i] = (il_sensor){{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}};
            if (!seen[i])
                continue;
            il_surface surf;
            il_scene_surface(scene, hit.mesh, hit.prim, hit.b1, hit.b2, &surf);
            il_vec3 n = v3_dot(surf.ns, ray.dir) > 0.0f ? v3_neg(surf.ns) : surf.ns;
            sensors[i] = (il_sensor){surf.p, n};
        }
    }
    return IL_OK;
}
