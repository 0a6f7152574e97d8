/* The size of the part of a scene the camera sees.
 *
 * Default radii that are fractions of the bounding box's diagonal suit a
 * scene the camera looks at as a whole (the Cornell box), not a room that
 * stands on an 80 m ground (scenes/window-room.json: a diagonal of 113 m
 * for a room of 7 m).  There the photon maps' and SPPM's first radii came
 * out at metres: every look-up searched a wide neighbourhood, and SPPM's
 * passes each spent seconds on photons that updated thousands of pixels
 * apiece.  What the camera sees sets the scale of what the image needs;
 * the percentiles leave out the few far points seen through a window.
 * The bounding box's diagonal stays wherever the view covers at least half
 * of it, so such scenes keep their radii exactly. */
#include "methods/view_size.h"

#include <math.h>
#include <stdlib.h>

#include "scene/camera.h"
#include "scene/portal.h"
#include "trace/trace.h"

#define GRID 32

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* The points a GRID x GRID grid of camera rays hits, their coordinates in
 * axis[0..2] (allocated here, freed by the caller, also when it returns
 * 0); with inside_only, not those seen through a portal from its lit side
 * (outside the interior the portals open).  Their number; 0 when out of
 * memory. */
static uint32_t camera_hits(const il_scene *s, bool inside_only, float *axis[3])
{
    for (int c = 0; c < 3; c++)
        axis[c] = malloc(GRID * GRID * sizeof(float));
    if (!axis[0] || !axis[1] || !axis[2])
        return 0;
    il_camera cam;
    il_camera_init(&cam, &s->camera.desc, GRID, GRID);
    uint32_t n = 0;
    for (uint32_t y = 0; y < GRID; y++)
        for (uint32_t x = 0; x < GRID; x++) {
            il_ray ray = {.org = cam.position, .tmin = 0.0f,
                          .dir = il_camera_ray_dir(&cam, x + 0.5f, y + 0.5f), .tmax = INFINITY};
            il_hit hit;
            if (!il_trace_closest(s->tracer, &ray, &hit))
                continue;
            il_vec3 p = v3_fma(ray.org, ray.dir, hit.t);
            /* Seen through a portal: the way back to the camera enters by it. */
            if (inside_only && il_portal_entered(s, p, v3_neg(ray.dir), hit.t, 1e-4f * hit.t, NULL))
                continue;
            axis[0][n] = p.x;
            axis[1][n] = p.y;
            axis[2][n] = p.z;
            n++;
        }
    return n;
}

float il_view_size(const il_scene *s)
{
    float diagonal = v3_length(v3_sub(s->bounds_max, s->bounds_min));
    if (!(diagonal > 0.0f))
        return 1.0f;
    if (!s->tracer)
        return diagonal;
    float *axis[3];
    uint32_t n = camera_hits(s, false, axis);
    float seen = diagonal;
    if (n >= GRID) {   /* a view of mostly sky keeps the box */
        float extent[3];
        for (int c = 0; c < 3; c++) {
            qsort(axis[c], n, sizeof(float), compare_floats);
            extent[c] = axis[c][n - 1 - n / 20] - axis[c][n / 20];
        }
        seen = v3_length(v3(extent[0], extent[1], extent[2]));
    }
    for (int c = 0; c < 3; c++)
        free(axis[c]);
    return seen > 0.0f && seen < 0.5f * diagonal ? seen : diagonal;
}

bool il_view_interior(const il_scene *s, il_vec3 *lo, il_vec3 *hi)
{
    *lo = s->bounds_min;
    *hi = s->bounds_max;
    float diagonal = v3_length(v3_sub(s->bounds_max, s->bounds_min));
    if (s->num_portals == 0 || !s->tracer || !(diagonal > 0.0f))
        return false;
    float *axis[3];
    uint32_t n = camera_hits(s, true, axis);
    bool smaller = false;
    if (n >= GRID) {
        il_vec3 a = v3(axis[0][0], axis[1][0], axis[2][0]), b = a;
        for (uint32_t i = 1; i < n; i++) {
            il_vec3 p = v3(axis[0][i], axis[1][i], axis[2][i]);
            a = v3_min(a, p);
            b = v3_max(b, p);
        }
        float seen = v3_length(v3_sub(b, a));
        if (seen > 0.0f && seen < 0.5f * diagonal) {
            *lo = a;
            *hi = b;
            smaller = true;
        }
    }
    for (int c = 0; c < 3; c++)
        free(axis[c]);
    return smaller;
}
