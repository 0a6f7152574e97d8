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
#include "trace/trace.h"

#define GRID 32

static int compare_floats(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

float il_view_size(const il_scene *s)
{
    float diagonal = v3_length(v3_sub(s->bounds_max, s->bounds_min));
    if (!(diagonal > 0.0f))
        return 1.0f;
    if (!s->tracer)
        return diagonal;
    float *axis[3];
    for (int c = 0; c < 3; c++)
        axis[c] = malloc(GRID * GRID * sizeof(float));
    uint32_t n = 0;
    if (axis[0] && axis[1] && axis[2]) {
        il_camera cam;
        il_camera_init(&cam, &s->camera.desc, GRID, GRID);
        for (uint32_t y = 0; y < GRID; y++)
            for (uint32_t x = 0; x < GRID; x++) {
                il_ray ray = {.org = cam.position, .tmin = 0.0f,
                              .dir = il_camera_ray_dir(&cam, x + 0.5f, y + 0.5f), .tmax = INFINITY};
                il_hit hit;
                if (!il_trace_closest(s->tracer, &ray, &hit))
                    continue;
                il_vec3 p = v3_fma(ray.org, ray.dir, hit.t);
                axis[0][n] = p.x;
                axis[1][n] = p.y;
                axis[2][n] = p.z;
                n++;
            }
    }
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
