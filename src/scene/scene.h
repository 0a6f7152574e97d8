/* The in-memory scene: what loaders fill and what every method reads.
 * Everything is in world space and validated on the way in (il_scene_add_*).
 * After il_scene_commit the scene is read-only and also holds the ray-casting
 * structure and the light tables. */
#ifndef IL_SCENE_SCENE_H
#define IL_SCENE_SCENE_H

#include <stdint.h>
#include "core/vec.h"
#include "illum/illum.h"

#define IL_NAME_MAX 64
#define IL_NO_LIGHT UINT32_MAX

typedef struct il_tracer il_tracer;
typedef struct il_envmap il_envmap;
typedef struct il_portal il_portal;

/* Per-triangle geometry that il_scene_commit precomputes for the surface
 * queries (il_scene_surface, il_scene_point): the three corners and their
 * vertex indices, read from one record instead of through the index buffer,
 * and the unit geometric normal of their winding,
 * normalize(cross(p1 - p0, p2 - p0)), which would otherwise cost a square
 * root and a division at every hit.  One 64-byte record (a cache line) per
 * triangle, contiguous per mesh. */
typedef struct il_tri_geom {
    il_vec3 p0, p1, p2;
    il_vec3 ng;
    uint32_t v[3];         /* the vertex indices (for normals and uvs) */
    uint32_t pad;
} il_tri_geom;

typedef struct il_mesh {
    char name[IL_NAME_MAX];
    uint32_t num_vertices;
    uint32_t num_triangles;
    il_vec3 *positions;
    il_vec3 *normals;      /* NULL: flat shading with the geometric normal */
    il_vec2 *uvs;          /* NULL: no texture coordinates */
    uint32_t *indices;     /* 3 per triangle */
    uint32_t material;
    il_tri_geom *geom;     /* num_triangles records, filled by il_scene_commit (NULL before) */
} il_mesh;

typedef struct il_texture {
    uint32_t width, height;
    float *rgb;            /* linear RGB, rows top to bottom */
} il_texture;

/* Mirror, glass and panes: every lobe a delta (no light sampling, no
 * radiosity patch). */
#define IL_MATERIAL_IS_DELTA(type) \
    ((type) == IL_MATERIAL_MIRROR || (type) == IL_MATERIAL_DIELECTRIC || \
     (type) == IL_MATERIAL_THIN_GLASS)

typedef struct il_material {
    char name[IL_NAME_MAX];
    il_material_type type;
    il_vec3 diffuse;
    uint32_t diffuse_texture;  /* 0: none; else index+1 into scene->textures */
    il_vec3 specular;          /* defaults resolved: MIRROR/DIELECTRIC tint is white when given as zero */
    float exponent;            /* resolved: never 0 for PHONG */
    float ior;                 /* resolved: never 0 */
    float pane_tau;            /* THIN_GLASS: internal transmittance per normal pass
                                  (scene/pane.h), from il_material_desc.transmittance */
    il_vec3 emission;
    bool two_sided;
} il_material;

/* Every light the integrators sample, one table: the user's point, spot and
 * directional lights, one entry per emissive triangle, and the environment. */
typedef enum il_light_kind {
    IL_LIGHTK_POINT = 0,
    IL_LIGHTK_SPOT,
    IL_LIGHTK_DIRECTIONAL,
    IL_LIGHTK_AREA,        /* one emissive triangle */
    IL_LIGHTK_ENVIRONMENT
} il_light_kind;

typedef struct il_light {
    il_light_kind kind;
    il_vec3 position;      /* POINT, SPOT */
    il_vec3 direction;     /* SPOT, DIRECTIONAL: unit, the way light travels */
    il_vec3 intensity;     /* POINT/SPOT W/sr; DIRECTIONAL W/m^2 */
    float cos_cutoff;      /* SPOT: cos of the cut-off half-angle; DIRECTIONAL: cos of its
                              disc's angular radius (1: a point) */
    float spot_exponent;   /* SPOT */
    uint32_t mesh, prim;   /* AREA: the triangle */
    float area;            /* AREA: the triangle's area */
    il_vec3 radiance;      /* AREA, ENVIRONMENT: emitted radiance */
    bool two_sided;        /* AREA */
    float power;           /* total emitted power (luminance-weighted), for selection */
} il_light;

/* A light as the batched light sampling (methods/diffuse_wave.c) reads it,
 * in one record instead of four tables.  kind says which lights it takes:
 * a triangle of a mesh without authored normals (whose normal is
 * il_tri_geom.ng), a point light, a spot light, a directional light, the
 * environment (sampled per vertex by il_environment_sample), each with a
 * non-zero selection probability pmf; IL_LREC_NONE for the others (a
 * triangle of a mesh with normals, a light never selected), which the
 * scalar il_light_sample_at samples. */
typedef enum il_lrec_kind {
    IL_LREC_NONE = 0, IL_LREC_TRIANGLE, IL_LREC_POINT, IL_LREC_SPOT, IL_LREC_DIRECTIONAL, IL_LREC_ENVIRONMENT
} il_lrec_kind;
typedef struct il_light_rec {
    il_vec3 p0, p1, p2;    /* TRIANGLE: the vertices; POINT, SPOT: p0 the position;
                              SPOT: p1 the unit axis it shines along;
                              DIRECTIONAL: p0 the unit direction towards the light (its
                              disc's centre) */
    il_vec3 ng;            /* TRIANGLE: the unit normal; else zero */
    il_vec3 radiance;      /* TRIANGLE: emitted radiance; POINT, SPOT: intensity; DIRECTIONAL:
                              irradiance (ENVIRONMENT: only pmf is used) */
    float area, pmf;       /* area: TRIANGLE */
    float cos_cutoff, spot_exponent; /* SPOT: il_light's; DIRECTIONAL: cos_cutoff as il_light's */
    bool two_sided;        /* TRIANGLE */
    il_lrec_kind kind;
} il_light_rec;

/* A directional light's disc as the camera sees it (the sun): the
 * directions within its angular radius of `towards` carry `radiance`.
 * Membership is tested on the sine, |dir x towards|^2 <= sin2_radius (and
 * dir . towards > 0): for a disc as small as the sun's, 1 - cos is 10^-5
 * and a float dot product would blur its edge by a per cent. */
typedef struct il_light_disc {
    il_vec3 towards;       /* unit, from the scene to the disc's centre */
    float sin2_radius;     /* sin^2 of the angular radius of the light's cos_cutoff */
    il_vec3 radiance;      /* irradiance / (pi sin2_radius) */
} il_light_disc;

typedef struct il_scene_camera {
    il_camera_desc desc;   /* defaults resolved */
    bool present;
} il_scene_camera;

struct il_scene {
    il_mesh *meshes;        uint32_t num_meshes, cap_meshes;
    il_material *materials; uint32_t num_materials, cap_materials;
    il_texture *textures;   uint32_t num_textures, cap_textures;
    il_light_desc *user_lights; uint32_t num_user_lights, cap_user_lights;
    bool has_sky_sun;       /* user_lights[sky_sun] is the sun il_scene_set_daylight added:
                               it goes with its sky when the environment is replaced */
    uint32_t sky_sun;
    bool has_daylight;      /* the environment is the sky il_scene_set_daylight set: */
    il_sky_desc daylight;   /* ... as set, defaults filled in */
    il_scene_camera camera;
    il_environment_desc environment; /* as given, but map is NULL (the map lives in envmap)
                                        and, with a map, radiance is its mean radiance */
    il_envmap *envmap;      /* the environment map with its sampling tables (image/envmap.h);
                               NULL for a constant sky */
    bool has_environment;   /* a constant sky of nonzero radiance, or a map with some light */
    il_portal *portals;     /* the environment's portals, one per triangle (scene/portal.h) */
    uint32_t num_portals;

    char **warnings;        uint32_t num_warnings, cap_warnings;
    uint64_t dropped_triangles;
    il_render_settings render_settings; /* from a JSON scene's "render" block (load_json.c) */
    bool has_render_settings;
    il_log_fn log;          /* receives every warning as it is recorded */
    void *log_user;

    /* Filled by il_scene_commit. */
    bool committed;
    il_vec3 bounds_min, bounds_max;
    float scene_radius;              /* of the bounding sphere */
    il_vec3 scene_center;
    il_tracer *tracer;
    il_light *lights;       uint32_t num_lights;
    float *light_cdf;                /* num_lights+1 entries, selection by power */
    float *light_pmf;                /* num_lights entries */
    uint32_t **triangle_light;       /* per mesh, per triangle: index into lights or IL_NO_LIGHT */
    il_light_rec *light_recs;        /* num_lights entries: what batched sampling reads of a light */
    uint32_t environment_light;      /* index into lights or IL_NO_LIGHT */
    il_light_disc *discs;   uint32_t num_discs; /* the directional lights with a disc */
    bool portal_light;      /* portals, and light from outside (the environment or a
                               directional light): light paths enter by the portals
                               (methods/portal_light.h) */
};

/* Records a warning (printf format): stored for `illum info` and passed to the log callback. */
void il_scene_warn(il_scene *scene, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Surface attributes at a hit: position, normals, uv, the material. */
typedef struct il_surface {
    il_vec3 p;
    il_vec3 ng;            /* geometric normal, unit; turned to the side of the vertex normals when the mesh has them */
    il_vec3 ns;            /* shading normal, unit (ng when the mesh has no normals) */
    il_vec2 uv;
    uint32_t mesh, prim;
    const il_material *material;
} il_surface;

/* Fills the surface attributes of triangle (mesh, prim) at barycentrics (b1, b2). */
void il_scene_surface(const il_scene *scene, uint32_t mesh, uint32_t prim, float b1, float b2,
                      il_surface *out);

/* Only the point and the geometric normal of il_scene_surface (the same
 * values, bit for bit): what sampling a point on an emitter needs. */
void il_scene_point(const il_scene *scene, uint32_t mesh, uint32_t prim, float b1, float b2,
                    il_vec3 *p, il_vec3 *ng);

/* The diffuse albedo at a surface point (texture times colour). */
il_vec3 il_material_diffuse(const il_scene *scene, const il_material *m, il_vec2 uv);

/* Texture lookup, bilinear, wrapping. */
il_vec3 il_texture_sample(const il_texture *tex, il_vec2 uv);

#endif
