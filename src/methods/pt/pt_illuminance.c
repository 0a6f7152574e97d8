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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/color.h"
#include "core/error.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "methods/pt/pt.h"
#include "scene/camera.h"

#define BLOCK_SAMPLES 64u           /* most samples of one sensor in one work item */
#define WAVE_PATHS 256u             /* most paths traced together (il_pt_sensor_wave_max) */
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
    for (size_t i = 0; i < count; i++) {
        il_vec3 p = sensors[i].position, n = sensors[i].normal;
        if (!v3_is_finite(p) || !v3_is_finite(n))
            return il_fail(err, IL_ERR_INVALID, "illuminance: sensor %zu has a NaN or infinite coordinate", i);
        if (!(v3_length(n) > 0.0f))
            return il_fail(err, IL_ERR_INVALID, "illuminance: sensor %zu has a zero normal", i);
    }
    return IL_OK;
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

/* The work items [first, last) of a round, item it being block done +
 * it % nb of sensor it / nb: their paths traced as one wave (at most
 * il_pt_sensor_wave_max paths), each item's sums formed in sample order. */
typedef struct round_ctx {
    const il_scene *scene;
    const il_illuminance_desc *desc;
    const il_sensor *sensors;
    const il_vec3 *normals;
    uint32_t max_depth, samples, block, done, nb;
} round_ctx;

static void sample_items(const round_ctx *c, int64_t first, int64_t last, void *scratch,
                         block_sum *part)
{
    il_vec3 p[WAVE_PATHS] = {{0}}, n[WAVE_PATHS] = {{0}}, e[WAVE_PATHS];
    il_sampler smp[WAVE_PATHS] = {{0}};
    uint32_t count = 0;
    for (int64_t it = first; it < last; it++) {
        size_t i = (size_t)(it / c->nb);
        uint32_t from = (c->done + (uint32_t)(it % c->nb)) * c->block;
        uint32_t to = c->samples - from < c->block ? c->samples : from + c->block;
        for (uint32_t k = from; k < to; k++, count++) {
            p[count] = c->sensors[i].position;
            n[count] = c->normals[i];
            il_sampler_start(&smp[count], c->desc->sampler, c->desc->seed, i, k);
        }
    }
    uint64_t rays = 0;
    il_pt_sensor_wave(c->scene, c->max_depth, scratch, p, n, smp, count, e, &rays);
    count = 0;
    for (int64_t it = first; it < last; it++) {
        block_sum *b = &part[it];
        memset(b, 0, sizeof *b);
        uint32_t from = (c->done + (uint32_t)(it % c->nb)) * c->block;
        uint32_t to = c->samples - from < c->block ? c->samples : from + c->block;
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

    double t0 = omp_get_wtime();
    uint32_t done = 0;                  /* blocks of every sensor added so far */
    while (done < blocks && count > 0) {
        uint32_t nb = blocks - done < round_blocks ? blocks - done : round_blocks;
        int64_t items = (int64_t)count * nb;
        /* Items in waves of as many whole blocks as a wave holds. */
        uint32_t wave = il_pt_sensor_wave_max() < WAVE_PATHS ? il_pt_sensor_wave_max() : WAVE_PATHS;
        int64_t per_wave = wave / block;
        int64_t waves = (items + per_wave - 1) / per_wave;
        round_ctx c = {scene, desc, sensors, normals, max_depth, samples, block, done, nb};
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

/* Whether `name` contains `part`, ignoring case. */
static bool contains(const char *name, const char *part)
{
    size_t n = strlen(part);
    for (const char *p = name; *p; p++)
        if (!strncasecmp(p, part, n))
            return true;
    return n == 0;
}

static bool mesh_matches(const il_scene *scene, const il_mesh *m, const char *part)
{
    return contains(m->name, part) ||
           (m->material < scene->num_materials && contains(scene->materials[m->material].name, part));
}

/* The "(meshes: a, b, ...)" of the error for a name nothing matches. */
static void mesh_names(const il_scene *scene, char *out, size_t size)
{
    size_t len = (size_t)snprintf(out, size, "the scene's meshes:");
    for (uint32_t i = 0; i < scene->num_meshes && len < size; i++)
        len += (size_t)snprintf(out + len, size - len, "%s '%s'", i ? "," : "",
                                scene->meshes[i].name[0] ? scene->meshes[i].name : "(no name)");
}

il_status il_surface_sensors(const il_scene *scene, const il_surface_sensor_desc *desc,
                             il_sensor *out, size_t capacity, il_surface_sensor_info *info,
                             il_error *err)
{
    if (!scene || !desc || !info || (capacity > 0 && !out))
        return il_fail(err, IL_ERR_INVALID, "surface sensors: scene, options and info are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "surface sensors: the scene is not committed (call il_scene_commit)");
    float spacing = desc->spacing > 0.0f ? desc->spacing : 0.1f;
    if (!(spacing > 0.0f) || !isfinite(spacing) || !v3_is_finite(desc->facing))
        return il_fail(err, IL_ERR_INVALID, "surface sensors: the spacing and the facing direction must be finite");
    const char *part = desc->name ? desc->name : "";
    bool oriented = !v3_is_zero(desc->facing);
    il_vec3 facing = oriented ? v3_normalize(desc->facing) : desc->facing;
    memset(info, 0, sizeof *info);
    /* Systematic sampling along the matching area: the k-th sensor goes to
     * the triangle in which the running area passes (k + 1/2) spacing^2, so
     * every sensor stands for the same area, and small triangles share. */
    double cell = (double)spacing * spacing, placed_area = 0.0;
    uint32_t matched = 0;
    for (uint32_t mi = 0; mi < scene->num_meshes; mi++) {
        const il_mesh *m = &scene->meshes[mi];
        if (!mesh_matches(scene, m, part))
            continue;
        matched++;
        for (uint32_t t = 0; t < m->num_triangles; t++) {
            il_surface c;
            il_scene_surface(scene, mi, t, 1.0f / 3.0f, 1.0f / 3.0f, &c);
            if (oriented && v3_dot(c.ng, facing) < 0.70710678f)
                continue;
            const il_vec3 *v = m->positions;
            const uint32_t *ix = m->indices + 3 * (size_t)t;
            double area = 0.5 * v3_length(v3_cross(v3_sub(v[ix[1]], v[ix[0]]), v3_sub(v[ix[2]], v[ix[0]])));
            info->triangles++;
            info->area += area;
            size_t before = (size_t)floor(placed_area / cell + 0.5);
            placed_area += area;
            size_t n = (size_t)floor(placed_area / cell + 0.5) - before;
            for (size_t k = 0; k < n; k++, info->count++) {
                if (info->count >= capacity)
                    continue;
                /* One sensor: the centroid; more: a Hammersley set. */
                il_vec2 b = {1.0f / 3.0f, 1.0f / 3.0f};
                if (n > 1) {
                    float y = il_sobol02((uint32_t)k).x + 0.5f / (float)n;
                    b = il_sample_triangle((il_vec2){((float)k + 0.5f) / (float)n, y < 1.0f ? y : y - 1.0f});
                }
                il_surface sp;
                il_scene_surface(scene, mi, t, b.x, b.y, &sp);
                out[info->count] = (il_sensor){sp.p, sp.ng};
            }
        }
    }
    if (matched > 0 && info->triangles == 0)
        return il_fail(err, IL_ERR_INVALID, "surface sensors: no triangle of the %u meshes named like "
                       "'%s' faces within 45 degrees of (%g, %g, %g)", matched, part,
                       (double)facing.x, (double)facing.y, (double)facing.z);
    if (info->triangles == 0) {
        char names[400];
        mesh_names(scene, names, sizeof names);
        return il_fail(err, IL_ERR_INVALID, "surface sensors: no mesh or material named like '%s' (%s)",
                       part, names);
    }
    return IL_OK;
}
