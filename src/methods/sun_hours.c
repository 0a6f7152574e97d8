/* il_sun_hours: how long the sun shines on each sensor over a period
 * (docs/illuminance.md#sun-hours).  The sun's places are found once, at
 * the middle of every step it stands above the minimum altitude; then each
 * sensor casts a shadow ray towards each place in front of it. */
#include <math.h>
#include <stdlib.h>

#include <omp.h>

#include "core/error.h"
#include "image/sky.h"
#include "methods/sensor_check.h"
#include "illum/illum.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* The longest period: a leap year; the most steps: a leap year of minutes
 * ten times over (the sun's places take 20 bytes a step). */
#define MAX_HOURS (366.0 * 24.0)
#define MAX_STEPS 5270400.0

static il_status check(const il_scene *scene, const il_sensor *sensors, size_t count,
                       const il_sun_hours_desc *d, double *hours, il_error *err)
{
    if (!scene || !d || (count > 0 && (!sensors || !hours)))
        return il_fail(err, IL_ERR_INVALID, "sun hours: scene, sensors, options and output are required");
    if (!(d->latitude >= -90.0 && d->latitude <= 90.0) || !(d->longitude >= -180.0 && d->longitude <= 180.0))
        return il_fail(err, IL_ERR_INVALID, "sun hours: latitude must be -90 to 90 and longitude -180 to 180 degrees");
    if (!isfinite(d->start))
        return il_fail(err, IL_ERR_INVALID, "sun hours: the start must be a finite number of seconds");
    if (!(d->hours >= 0.0 && d->hours <= MAX_HOURS))
        return il_fail(err, IL_ERR_INVALID, "sun hours: the period must be 0 to %g hours (a leap year)", MAX_HOURS);
    if (!(d->step_minutes >= 0.0 && d->step_minutes <= 60.0))
        return il_fail(err, IL_ERR_INVALID, "sun hours: the step must be 0 to 60 minutes");
    double period = d->hours > 0.0 ? d->hours : 24.0, step = d->step_minutes > 0.0 ? d->step_minutes : 1.0;
    if (period * 60.0 / step > MAX_STEPS)
        return il_fail(err, IL_ERR_INVALID, "sun hours: %.0f steps of %g minutes are more than %.0f; take longer steps",
                       ceil(period * 60.0 / step), step, MAX_STEPS);
    if (!(d->min_altitude >= 0.0 && d->min_altitude < 90.0))
        return il_fail(err, IL_ERR_INVALID, "sun hours: the minimum altitude must be at least 0 and below 90 degrees");
    if (!isfinite(d->north) || fabs(d->north) > 1e6)
        return il_fail(err, IL_ERR_INVALID, "sun hours: north must be a finite number of degrees");
    return il_sensors_check("sun hours", sensors, count, err);
}

il_status il_sun_hours(const il_scene *scene, const il_sensor *sensors, size_t count,
                       const il_sun_hours_desc *desc, double *hours, il_sun_hours_stats *stats,
                       il_error *err)
{
    il_sun_hours_stats local = {0};
    if (!stats)
        stats = &local;
    *stats = (il_sun_hours_stats){0};
    il_status st = check(scene, sensors, count, desc, hours, err);
    if (st != IL_OK)
        return st;
    double t0 = omp_get_wtime();
    double period = desc->hours > 0.0 ? desc->hours : 24.0;
    double step = desc->step_minutes > 0.0 ? desc->step_minutes : 1.0;
    size_t steps = (size_t)ceil(period * 60.0 / step - 1e-9);
    if (steps == 0)
        steps = 1; /* a period shorter than a billionth of its step */
    /* The last step may be shorter: it ends with the period. */
    double last = period * 60.0 - (double)(steps - 1) * step;

    /* Where the sun stands at the middle of each step, while above the
     * minimum altitude, and how many minutes the step holds. */
    il_vec3 *towards = malloc(steps * sizeof *towards);
    double *minutes = malloc(steps * sizeof *minutes), *ends = malloc(steps * sizeof *ends);
    if (!towards || !minutes || !ends) {
        free(towards);
        free(minutes);
        free(ends);
        return il_fail(err, IL_ERR_MEMORY, "sun hours: out of memory for %zu steps", steps);
    }
    size_t up = 0;
    for (size_t k = 0; k < steps; k++) {
        double len = k + 1 == steps ? last : step;
        double alt, az;
        st = il_sun_position(desc->latitude, desc->longitude, desc->start + 60.0 * ((double)k * step + 0.5 * len),
                             &alt, &az, err);
        if (st != IL_OK) {
            free(towards);
            free(minutes);
            free(ends);
            return st;
        }
        if (alt > desc->min_altitude) {
            towards[up] = il_sky_direction(alt, az, desc->north);
            ends[up] = (double)k * step + len; /* minutes from the start to the step's end */
            minutes[up++] = len;
        }
    }

    /* A committed scene has its tracer; else one is built for this call. */
    il_tracer *own = NULL;
    const il_tracer *tracer = scene->tracer;
    if (!tracer) {
        if ((st = il_tracer_create(scene, &own, err)) != IL_OK) {
            free(towards);
            free(minutes);
            free(ends);
            return st;
        }
        tracer = own;
    }
    /* Minutes summed per sensor, the sun's places in order, in rounds of
     * about a hundredth of them (fewer when that would be more than about
     * a million rays), after each of which progress may stop it. */
    for (size_t i = 0; i < count; i++)
        hours[i] = 0.0;
    uint64_t rays = 0;
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    size_t round = up / 100 + 1, done = 0;
    if (count > 0 && round * count > 1000000u)
        round = 1000000u / count > 0 ? 1000000u / count : 1u;
    double covered = period * 60.0;
    while (done < up) {
        size_t end = done + round < up ? done + round : up;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 16) reduction(+ : rays)
        for (size_t i = 0; i < count; i++) {
            il_vec3 p = sensors[i].position, n = v3_normalize(sensors[i].normal);
            for (size_t k = done; k < end; k++) {
                if (!(v3_dot(n, towards[k]) > 0.0f))
                    continue;
                il_ray ray = {.org = il_offset_origin(tracer, p, n, towards[k]), .tmin = 0.0f,
                              .dir = towards[k], .tmax = INFINITY};
                rays++;
                if (!il_trace_occluded(tracer, &ray))
                    hours[i] += minutes[k];
            }
        }
        done = end;
        if (done < up && desc->progress &&
            !desc->progress((double)done / (double)up, omp_get_wtime() - t0, desc->progress_user)) {
            stats->stopped = true;
            covered = ends[done - 1];
            break;
        }
    }
    double up_minutes = 0.0; /* summed as a sensor's minutes are */
    for (size_t k = 0; k < done; k++)
        up_minutes += minutes[k];
    for (size_t i = 0; i < count; i++)
        hours[i] /= 60.0;
    il_tracer_release(own);
    free(towards);
    free(minutes);
    free(ends);
    stats->sun_up_hours = up_minutes / 60.0;
    stats->hours_done = covered / 60.0;
    stats->rays = rays;
    stats->seconds = omp_get_wtime() - t0;
    return IL_OK;
}
