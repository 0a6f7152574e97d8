/* Environment maps: the sky as an image of radiance, its three mappings
 * between directions and texels, bilinear lookups, rotation, and (in
 * envmap_sample.c) the tables that importance-sample it.
 * docs/environment.md draws each mapping and derives the formulas.
 *
 * Directions point AWAY from the scene, towards the sky; +y is up.
 * Image coordinates (u, v) are in [0,1]^2 over the whole image, u to the
 * right, v downwards (v = 0 is the top row, as il_image stores rows).
 *
 * Lat-long (equirectangular, any size, 2:1 usual):
 *   theta = pi v (angle from +y), phi = 2 pi (u - 1/2),
 *   dir = (sin theta sin phi, cos theta, -sin theta cos phi).
 *   The top row is +y, the bottom row -y; the image's centre column
 *   (u = 1/2) is -z, u = 3/4 is +x, u = 1/4 is -x and both side edges are +z:
 *   a camera looking down -z with +y up sees the middle of the panorama
 *   the right way round.
 *
 * Angular map (Debevec's light probe, square):
 *   (a, b) = (Dx, Dy) acos(Dz) / (pi sqrt(Dx^2 + Dy^2)) in [-1,1]^2, a to
 *   the right, b up; u = (a + 1)/2, v = (1 - b)/2.  The formula is taken
 *   in world axes: the image centre is +z, the rim (radius 1) is -z, +x is
 *   to the right and +y up.  That is the mirror ball photographed by a
 *   camera on the +z side looking down -z (the ball's centre reflects what
 *   is behind the camera), unwrapped so that the radius grows linearly with
 *   the angle from +z.  Texels outside the unit disk are not part of the sky.
 *
 * Vertical cross (3 faces wide, 4 tall; face size F = width/3 = height/4):
 *
 *          +----+
 *          | +y |             each face as seen from inside the cube:
 *     +----+----+----+        face  centre  right  up
 *     | -x | -z | +x |        -z    -z      +x     +y   (front, the middle)
 *     +----+----+----+        +x    +x      +z     +y
 *          | -y |             -x    -x      -z     +y
 *          +----+             +y    +y      +x     +z
 *          | +z |             -y    -y      +x     -z
 *          +----+             +z    +z      +x     -y   (upside down)
 *
 *   A direction d on face (c, r, t) sits at a = d.r / d.c, b = d.t / d.c in
 *   [-1,1]^2, a to the right and b up within the face's cell.  Neighbouring
 *   cells of the cross share their edges on the cube, so the cross folds
 *   into it (the back face hangs below the bottom one, hence upside down).
 *   The six empty cells are not part of the sky.
 *
 * Lookups are bilinear between texel centres: lat-long wraps around in u
 * and clamps at the poles; the angular map leaves out the texels wholly
 * outside its disk (renormalising the others' weights), so a probe's black
 * border does not darken the rim; the cross filters within one face only
 * and clamps at its edges, so nothing bleeds in from an empty cell or from
 * a face that is not adjacent. */
#ifndef IL_IMAGE_ENVMAP_H
#define IL_IMAGE_ENVMAP_H

#include <stdbool.h>
#include <stdint.h>

/* The largest radiance a map's texel may hold (times its intensity): the
 * sampling tables sum texels, and a sum beyond 3.4e38 would be infinite. */
#define IL_ENVMAP_MAX_RADIANCE 1e30f

#include "core/sampling.h"
#include "core/vec.h"
#include "illum/illum.h"

/* The name of a mapping: "latlong", "angular", "cross". */
const char *il_envmap_mapping_name(il_env_mapping m);
/* Parses a mapping name; false when it is none of the three. */
bool il_envmap_mapping_from_name(const char *name, il_env_mapping *out);
/* The mapping an image of this size most likely uses: 1:1 angular, 3:4
 * cross, anything else (2:1 above all) lat-long. */
il_env_mapping il_envmap_mapping_for_size(uint32_t width, uint32_t height);

/* Checks that an image can be an environment map of mapping m: its size
 * (angular square, cross 3:4 with a width divisible by 3, lat-long at least
 * 2 x 1) and its texels (every value finite; negative values are allowed
 * here and clamped to zero by il_envmap_init).  `what` names the image in
 * the message (a file name, "environment map"). */
il_status il_envmap_check(const il_image *img, il_env_mapping m, const char *what, il_error *err);

/* Direction (unit, any) -> image coordinates in [0,1]^2. */
il_vec2 il_envmap_dir_to_uv(il_env_mapping m, il_vec3 dir);
/* Image coordinates -> unit direction; false where the image holds no sky
 * (outside the angular map's disk, an empty cell of the cross). */
bool il_envmap_uv_to_dir(il_env_mapping m, il_vec2 uv, il_vec3 *dir);
/* dOmega / d(u,v): the solid angle per unit of image area at uv (lat-long
 * 2 pi^2 sin theta; angular 4 pi sin(pi r) / r with r the radius in the
 * unit disk; cross 48 / (1 + a^2 + b^2)^(3/2), the cell being 1/12 of the
 * image); 0 outside the sky. */
float il_envmap_jacobian(il_env_mapping m, il_vec2 uv);
/* The lat-long direction of image coordinates (u, v) (also the cells of
 * the sampling grid). */
static inline il_vec3 il_envmap_latlong_dir(float u, float v)
{
    float theta = IL_PI * v, phi = 2.0f * IL_PI * (u - 0.5f);
    float st = sinf(theta);
    return v3(st * sinf(phi), cosf(theta), -st * cosf(phi));
}
/* Bilinear radiance of img (mapping m) from direction dir (unit, in the
 * map's own frame: no rotation). */
il_vec3 il_envmap_lookup(const il_image *img, il_env_mapping m, il_vec3 dir);
/* The same for a lat-long image at the point uv (il_envmap_dir_to_uv's). */
il_vec3 il_envmap_lookup_latlong_uv(const il_image *img, il_vec2 uv);

/* Importance sampling of the sky (envmap_sample.c): a piecewise-constant
 * density over a lat-long grid of cells (the map's own texels for a
 * lat-long map), marginal over the rows, conditional within each. */
typedef struct il_envmap_dist {
    uint32_t width, height;       /* the grid: width cells per row, height rows */
    il_distrib1d marginal;        /* height bins: which row */
    il_distrib1d *rows;           /* height distributions of width bins */
    il_vec3 mean;                 /* mean radiance over the sphere (solid angle) */
} il_envmap_dist;

/* A map ready to light a scene: texels times intensity, with the rotation
 * and the sampling tables. */
typedef struct il_envmap {
    il_env_mapping mapping;
    il_image img;                 /* owned; negative texels clamped to 0 */
    float rotation;               /* radians about +y, counter-clockwise from above */
    float cos_rot, sin_rot;
    il_envmap_dist dist;
} il_envmap;

/* Copies img (texels times intensity; intensity 0 means 1) and builds the
 * sampling tables.  *clamped (may be NULL) counts the negative texel values
 * set to zero.  rotation_deg: degrees about +y, counter-clockwise seen from above. */
il_status il_envmap_init(il_envmap *env, const il_image *img, il_env_mapping m, float rotation_deg,
                         float intensity, uint64_t *clamped, il_error *err);
void il_envmap_free(il_envmap *env);

/* World direction <-> the map's own frame: local = R_y(-rotation) world. */
static inline il_vec3 il_envmap_to_local(const il_envmap *env, il_vec3 d)
{
    return v3(d.x * env->cos_rot - d.z * env->sin_rot, d.y, d.x * env->sin_rot + d.z * env->cos_rot);
}
static inline il_vec3 il_envmap_to_world(const il_envmap *env, il_vec3 d)
{
    return v3(d.x * env->cos_rot + d.z * env->sin_rot, d.y, -d.x * env->sin_rot + d.z * env->cos_rot);
}

/* Radiance arriving from world direction dir (unit, pointing at the sky). */
static inline il_vec3 il_envmap_eval(const il_envmap *env, il_vec3 dir)
{
    return il_envmap_lookup(&env->img, env->mapping, il_envmap_to_local(env, dir));
}

/* envmap_sample.c: builds env->dist from env->img (called by il_envmap_init). */
il_status il_envmap_dist_build(il_envmap *env, il_error *err);
void il_envmap_dist_free(il_envmap_dist *d);
/* A world direction for u in [0,1)^2 with its solid-angle density *pdf
 * (0 when the sample failed: then the direction is not to be used);
 * returns the radiance from it. */
il_vec3 il_envmap_sample(const il_envmap *env, il_vec2 u, il_vec3 *dir, float *pdf);
/* The solid-angle density with which il_envmap_sample picks world dir. */
float il_envmap_pdf(const il_envmap *env, il_vec3 dir);
/* il_envmap_eval and il_envmap_pdf at once, the same values bit for bit: a
 * lat-long map turns dir into its texel coordinates once for both (the
 * two atan2f of il_envmap_dir_to_uv are a good part of a sky's cost). */
il_vec3 il_envmap_eval_pdf(const il_envmap *env, il_vec3 dir, float *pdf);

#endif
