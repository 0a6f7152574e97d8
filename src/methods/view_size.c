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

#include "core/rng.h"
#include "core/sampling.h"
#include "scene/camera.h"
#include "scene/portal.h"
#include "trace/trace.h"

#define GRID 32

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Whether the point p, reached along the unit dir after t, lies beyond a
 * portal from where the ray started: the way back enters by it. */
static bool through_portal(const il_scene *s, il_vec3 p, il_vec3 dir, float t)
{
    return il_portal_entered(s, p, v3_neg(dir), t, 1e-4f * t, NULL);
}

static void add_point(float *axis[3], uint32_t *n, il_vec3 p)
{
    axis[0][*n] = p.x;
    axis[1][*n] = p.y;
    axis[2][*n] = p.z;
    ++*n;
}

/* The points a GRID x GRID grid of camera rays hits, their coordinates in
 * axis[0..2] (allocated here, freed by the caller, also when it returns
 * 0).  With `interior`, not those seen through a portal from its lit side
 * (outside the interior the portals open), and from each point one
 * cosine-distributed ray more, whose hit (unless through a portal) adds
 * the room around what the camera sees: a close view of a wall still gets
 * the room.  Their number; 0 when out of memory. */
static uint32_t camera_hits(const il_scene *s, bool interior, float *axis[3])
{
    for (int c = 0; c < 3; c++)
        axis[c] = malloc(2 * GRID * GRID * sizeof(float));
    if (!axis[0] || !axis[1] || !axis[2])
        return 0;
    il_camera cam;
    il_camera_init(&cam, &s->camera.desc, GRID, GRID);
    il_pcg32 rng = il_pcg32_seed(0x766965u, 0);
    uint32_t n = 0;
    for (uint32_t y = 0; y < GRID; y++)
        for (uint32_t x = 0; x < GRID; x++) {
            il_ray ray = {.org = cam.position, .tmin = 0.0f,
                          .dir = il_camera_ray_dir(&cam, x + 0.5f, y + 0.5f), .tmax = INFINITY};
            il_hit hit;
            if (!il_trace_closest(s->tracer, &ray, &hit))
                continue;
            il_vec3 p = v3_fma(ray.org, ray.dir, hit.t);
            if (interior && through_portal(s, p, ray.dir, hit.t))
                continue;
            add_point(axis, &n, p);
            if (!interior)
                continue;
            il_vec3 q, ng;
            il_scene_point(s, hit.mesh, hit.prim, hit.b1, hit.b2, &q, &ng);
            if (v3_dot(ng, ray.dir) > 0.0f)
                ng = v3_neg(ng);
            il_frame f = il_frame_from_normal(ng);
            il_vec2 u = v2(il_pcg32_float(&rng), il_pcg32_float(&rng));
            il_vec3 d = il_frame_to_world(&f, il_sample_cosine_hemisphere(u));
            il_ray bounce = {.org = il_offset_origin(s->tracer, p, ng, d), .tmin = 0.0f, .dir = d,
                             .tmax = INFINITY};
            if (il_trace_closest(s->tracer, &bounce, &hit)) {
                il_vec3 p2 = v3_fma(bounce.org, d, hit.t);
                if (!through_portal(s, p2, d, hit.t))
                    add_point(axis, &n, p2);
            }
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
