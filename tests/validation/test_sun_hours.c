/* il_sun_hours (methods/sun_hours.c), hours of direct sun at sensors:
 * - open sky, facing up: every hour the sun stands above the horizon (the
 *   period's sun_up_hours); on the equinox at the equator that is 12 h and
 *   the few minutes refraction adds at each end (12.03-12.12 h); facing
 *   down, none; under a window pane (thin_glass) the same as the open sky;
 * - a tall wall just east of the sensor hides the whole morning, one just
 *   west the afternoon: the two add up to the open sky's hours (within the
 *   steps near noon, when the sun passes over both), each about half;
 * - north turned 90 degrees moves east to -z: a wall at -z then hides
 *   what the wall at +x hid;
 * - a minimum altitude of 30 degrees leaves the hours between the sun's
 *   passing 30 degrees up and down: at the equator on the equinox the sun
 *   climbs 15 degrees an hour, so about 8 h;
 * - a period whose last step is short counts it by its length;
 * - progress reports rising fractions below 1 and changes nothing; when it
 *   stops the count, the hours are those of the period up to the step
 *   reached (the same as a period ending there);
 * - committed or not, one thread or two: the same hours; bad input is
 *   refused. */
#include <math.h>

#include "scene_build.h"
#include "scene/sun.h"

/* 2026-03-20T12:00Z is about the March equinox (14:46 UTC that day): the
 * day at longitude 0 from its local midnight. */
static double equinox_midnight(void)
{
    double t;
    int day;
    il_error err = {0};
    CHECK_OK(il_parse_moment("2026-03-20T00:00Z", &t, &day, &err), &err);
    return t;
}

typedef struct progress_log {
    int calls, stop_after;
    double last;
    bool rising;
} progress_log;

static bool on_progress(double fraction, double seconds, void *user)
{
    progress_log *l = user;
    (void)seconds;
    l->rising = l->rising && fraction > l->last && fraction < 1.0;
    l->last = fraction;
    return ++l->calls != l->stop_after;
}

static il_scene *scene_with(il_vec3 wall_centre, il_vec3 ex, il_vec3 ey)
{
    il_scene *s = new_scene();
    uint32_t m = add_material(s, (il_material_desc){.diffuse = v3s(0.5f)});
    add_quad(s, wall_centre, ex, ey, m);
    return s;
}

static double hours_at(const il_scene *s, il_vec3 normal, il_sun_hours_desc d, il_sun_hours_stats *st)
{
    il_sensor sn = {v3(0, 0, 0), normal};
    double h = -1.0;
    il_error err = {0};
    CHECK_OK(il_sun_hours(s, &sn, 1, &d, &h, st, &err), &err);
    return h;
}

int main(void)
{
    const il_sun_hours_desc day = {.latitude = 0.0, .longitude = 0.0, .start = equinox_midnight()};
    const il_vec3 up = v3(0, 1, 0);
    /* Open sky: a small quad far below, only so the scene has geometry. */
    il_scene *open = scene_with(v3(0, -100, 0), v3(1, 0, 0), v3(0, 0, 1));
    il_sun_hours_stats st;
    double h_open = hours_at(open, up, day, &st);
    printf("open sky: %.4f h of sun, the sun up %.4f h, %llu rays\n", h_open, st.sun_up_hours,
           (unsigned long long)st.rays);
    CHECK(h_open == st.sun_up_hours);
    CHECK(h_open > 12.03 && h_open < 12.12);
    CHECK(st.rays == (uint64_t)llround(st.sun_up_hours * 60.0));
    CHECK(hours_at(open, v3(0, -1, 0), day, NULL) == 0.0);

    /* A window pane (thin_glass) over the sensor does not stop the sun. */
    il_scene *glazed = new_scene();
    add_floor(glazed, 1.0f, 50.0f, add_material(glazed, (il_material_desc){.type = IL_MATERIAL_THIN_GLASS}));
    double h_glazed = hours_at(glazed, up, day, NULL);
    printf("under a pane: %.4f h\n", h_glazed);
    CHECK(h_glazed == h_open);
    il_scene_release(glazed);

    /* Walls 0.5 m east (+x) and west (-x), 10 km high and long. */
    il_scene *east = scene_with(v3(0.5f, 0, 0), v3(0, 0, 2e4f), v3(0, 2e4f, 0));
    il_scene *west = scene_with(v3(-0.5f, 0, 0), v3(0, 0, 2e4f), v3(0, 2e4f, 0));
    double h_east = hours_at(east, up, day, NULL), h_west = hours_at(west, up, day, NULL);
    printf("wall east: %.4f h, wall west: %.4f h, sum %.4f h\n", h_east, h_west, h_east + h_west);
    CHECK(h_east + h_west >= h_open - 1e-9 && h_east + h_west <= h_open + 2.0 / 60.0);
    CHECK(fabs(h_east - h_west) < 0.05);
    il_sun_hours_desc turned = day;
    turned.north = 90.0; /* east is -z */
    il_scene *south = scene_with(v3(0, 0, -0.5f), v3(2e4f, 0, 0), v3(0, 2e4f, 0));
    double h_turned = hours_at(south, up, turned, NULL);
    printf("north turned 90, wall at -z: %.4f h\n", h_turned);
    CHECK(fabs(h_turned - h_east) <= 1.0 / 60.0 + 1e-9);

    il_sun_hours_desc high = day;
    high.min_altitude = 30.0;
    double h_high = hours_at(open, up, high, &st);
    printf("above 30 degrees: %.4f h\n", h_high);
    CHECK(h_high == st.sun_up_hours);
    CHECK(fabs(h_high - 8.0) < 0.05);

    /* 90 minutes about noon in steps of an hour: 60 + 30 minutes, the sun up all along. */
    il_sun_hours_desc noon = day;
    noon.start = day.start + 11.5 * 3600.0;
    noon.hours = 1.5;
    noon.step_minutes = 60.0;
    CHECK(hours_at(open, up, noon, &st) == 1.5 && st.sun_up_hours == 1.5 && st.rays == 2);

    /* Progress: reported, then stopping after the fifth round. */
    progress_log log = {.rising = true};
    il_sun_hours_desc watched = day;
    watched.progress = on_progress;
    watched.progress_user = &log;
    CHECK(hours_at(east, up, watched, &st) == h_east && !st.stopped && st.hours_done == 24.0);
    printf("progress: %d calls, rising %d\n", log.calls, (int)log.rising);
    CHECK(log.calls >= 90 && log.calls <= 100 && log.rising);
    log = (progress_log){.rising = true, .stop_after = 5};
    double h_stopped = hours_at(open, up, watched, &st);
    il_sun_hours_desc until = day;
    until.hours = st.hours_done;
    il_sun_hours_stats st_until;
    double h_until = hours_at(open, up, until, &st_until);
    printf("stopped after 5 rounds: %.4f h of sun in the first %.4f h (a period that long: %.4f h)\n",
           h_stopped, st.hours_done, h_until);
    CHECK(st.stopped && st.hours_done > 6.0 && st.hours_done < 7.0);
    CHECK(h_stopped == st.sun_up_hours && fabs(h_stopped - h_until) < 1e-9 && h_stopped > 0.0);

    /* Committed or not, one thread or two: the same hours for a grid of sensors. */
    enum { N = 64 };
    il_sensor grid[N];
    for (int i = 0; i < N; i++)
        grid[i] = (il_sensor){v3((float)(i % 8) - 3.5f, 0, (float)(i / 8) - 3.5f), v3(0.2f, 1, (float)(i % 3) - 1)};
    double a[N], b[N];
    il_sun_hours_desc d1 = day, d2 = day;
    d1.threads = 1;
    d2.threads = 2;
    il_error err = {0};
    CHECK_OK(il_sun_hours(east, grid, N, &d1, a, NULL, &err), &err);
    il_light_desc sun = {.type = IL_LIGHT_DIRECTIONAL, .intensity = v3s(1.0f)};
    CHECK_OK(il_scene_add_light(east, &sun, &err), &err);
    CHECK_OK(il_scene_commit(east, &err), &err);
    CHECK_OK(il_sun_hours(east, grid, N, &d2, b, NULL, &err), &err);
    for (int i = 0; i < N; i++)
        CHECK(a[i] == b[i]);

    /* Bad input. */
    il_sensor bad_sensor[2] = {{v3(0, 0, 0), v3(0, 0, 0)}, {v3(NAN, 0, 0), up}};
    il_sun_hours_desc bad[] = {day, day, day, day, day, day, day};
    bad[0].step_minutes = 61.0;
    bad[1].hours = -1.0;
    bad[2].latitude = 91.0;
    bad[3].min_altitude = 90.0;
    bad[4].start = -3e9; /* 1874 */
    bad[5].north = INFINITY;
    bad[6].hours = 8784.0; /* a leap year in steps of 0.001 minutes: too many */
    bad[6].step_minutes = 0.001;
    double h;
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        CHECK(il_sun_hours(open, &grid[0], 1, &bad[k], &h, NULL, &err) == IL_ERR_INVALID);
        printf("bad option %zu: %s\n", k, err.message);
    }
    for (int k = 0; k < 2; k++) {
        CHECK(il_sun_hours(open, &bad_sensor[k], 1, &day, &h, NULL, &err) == IL_ERR_INVALID);
        printf("bad sensor %d: %s\n", k, err.message);
    }
    CHECK(il_sun_hours(NULL, &grid[0], 1, &day, &h, NULL, &err) == IL_ERR_INVALID);
    il_scene_release(open);
    il_scene_release(east);
    il_scene_release(west);
    il_scene_release(south);
    return check_report();
}
