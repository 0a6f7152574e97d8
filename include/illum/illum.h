/*
 * illum — global illumination in C.  The whole public API is this header.
 *
 * Usage in short:
 *
 *     il_error err = {0};
 *     il_scene *scene = NULL;
 *     if (il_scene_load("cornell", NULL, &scene, &err) != IL_OK ||
 *         il_scene_commit(scene, &err) != IL_OK) { fprintf(stderr, "%s\n", err.message); ... }
 *     il_film *film = NULL;
 *     il_film_create(512, 512, &film, &err);
 *     il_render_desc rd = {.spp = 64};           // zero fields mean "the default"
 *     il_render(scene, film, &rd, NULL, &err);
 *     il_image img = {0};
 *     il_film_resolve(film, &img);
 *     il_image_write(&img, "out.exr", NULL, &err);
 *     il_image_free(&img); il_film_release(film); il_scene_release(scene);
 *
 * Conventions
 * - Every fallible call returns an il_status and, when `err` is not NULL, fills
 *   it with a one-line message naming the file or value at fault.
 * - Structs named *_desc configure work and are valid when zero-initialised:
 *   a zero field means the documented default.
 * - The library never prints and never exits; warnings and progress reach the
 *   caller through callbacks.  There is no global state: two scenes may be
 *   loaded and rendered from two threads.
 * - Units: right-handed, y up, metres.  Radiometric quantities are linear
 *   Rec.709 RGB: radiance in W/(sr m^2), intensity in W/sr, irradiance in W/m^2.
 *   An emissive surface emits its radiance from its front face only (the side
 *   its shading normal points to) unless marked two-sided.
 */
#ifndef ILLUM_H
#define ILLUM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define IL_VERSION_MAJOR 0
#define IL_VERSION_MINOR 1
#define IL_VERSION_PATCH 0
#define IL_VERSION_STRING "0.1.0"

/* ------------------------------------------------------------------ errors */

typedef enum il_status {
    IL_OK = 0,
    IL_ERR_IO,        /* a file could not be opened, read, written or renamed */
    IL_ERR_FORMAT,    /* a file is corrupt, truncated or of an unknown format */
    IL_ERR_INVALID,   /* bad input: absurd parameter, empty scene, no light */
    IL_ERR_MEMORY,    /* out of memory */
    IL_ERR_RUNTIME    /* a dependency (Embree, assimp, OpenEXR) failed */
} il_status;

typedef struct il_error {
    il_status status;
    char message[512];
} il_error;

const char *il_status_name(il_status status);

/* ------------------------------------------------------------ basic types */

typedef struct il_vec2 { float x, y; } il_vec2;
typedef struct il_vec3 { float x, y, z; } il_vec3;

typedef enum il_log_level { IL_LOG_INFO = 0, IL_LOG_WARNING } il_log_level;
typedef void (*il_log_fn)(il_log_level level, const char *message, void *user);

/* -------------------------------------------------------------- materials */

typedef enum il_material_type {
    IL_MATERIAL_DIFFUSE = 0, /* Lambertian: diffuse/pi */
    IL_MATERIAL_PHONG,       /* diffuse + normalised modified Phong lobe */
    IL_MATERIAL_MIRROR,      /* perfect specular reflection, tinted by `specular` */
    IL_MATERIAL_DIELECTRIC,  /* smooth glass: Fresnel reflection + refraction */
    IL_MATERIAL_THIN_GLASS   /* a window pane of negligible thickness: light passes
                                straight through or is reflected (docs/materials.md) */
} il_material_type;

typedef struct il_material_desc {
    const char *name;          /* copied; may be NULL */
    il_material_type type;
    il_vec3 diffuse;           /* diffuse albedo (DIFFUSE, PHONG); channels above 1
                                  are clamped to 1, with a scene warning */
    uint32_t diffuse_texture;  /* 0: none, else a handle from il_scene_add_texture;
                                  multiplies `diffuse` */
    il_vec3 specular;          /* PHONG: specular albedo.  MIRROR/DIELECTRIC: tint,
                                  zero means white; clamped to 1 as `diffuse` */
    float exponent;            /* PHONG: cos^n exponent; 0 means 32 */
    float ior;                 /* DIELECTRIC, THIN_GLASS: index of refraction; 0 means 1.5 */
    float transmittance;       /* THIN_GLASS: the pane's light transmittance at normal
                                  incidence (a glazing's tau_v, EN 410); 0 means clear
                                  glass without absorption, (1 - F0) / (1 + F0): 0.923
                                  at ior 1.5 */
    il_vec3 emission;          /* emitted radiance, W/(sr m^2); zero: not an emitter */
    bool two_sided;            /* emit from both faces */
} il_material_desc;

/* ----------------------------------------------------------------- lights */

typedef enum il_light_type {
    IL_LIGHT_POINT = 0,  /* intensity W/sr in every direction */
    IL_LIGHT_SPOT,       /* intensity W/sr on its axis, times cos^exponent of the
                            angle to the axis, zero beyond the cut-off angle */
    IL_LIGHT_DIRECTIONAL /* irradiance W/m^2 on a surface facing the light */
} il_light_type;

typedef struct il_light_desc {
    il_light_type type;
    il_vec3 position;    /* POINT, SPOT */
    il_vec3 direction;   /* SPOT, DIRECTIONAL: the direction light travels;
                            zero means straight down (0,-1,0) */
    il_vec3 intensity;   /* POINT/SPOT: W/sr; DIRECTIONAL: W/m^2 */
    float spot_angle;    /* SPOT: cut-off half-angle in degrees; 0 means 45 */
    float spot_exponent; /* SPOT: falloff exponent n of cos^n; 0 means none */
    float diameter;      /* DIRECTIONAL: the apparent diameter of its disc in degrees,
                            0 to 90 (the sun: 0.533), which softens shadow edges;
                            0 means a point: sharp shadows */
} il_light_desc;

/* How an environment map's texels cover the sphere of directions
 * (docs/environment.md draws each; +y is up). */
typedef enum il_env_mapping {
    IL_ENV_LATLONG = 0,  /* latitude-longitude (equirectangular), 2:1 */
    IL_ENV_ANGULAR,      /* Debevec's angular light probe, square */
    IL_ENV_CROSS         /* vertical cross of six cube faces, 3:4 */
} il_env_mapping;

/* Light from infinitely far away: the sky.  Without a map, a constant
 * radiance from every direction; with a map, the map's texels are radiance
 * in W/(sr m^2), linear Rec.709. */
typedef struct il_environment_desc {
    il_vec3 radiance;    /* no map: W/(sr m^2) arriving from every direction;
                            ignored when map is set */
    const struct il_image *map; /* optional environment map; copied by
                                   il_scene_set_environment */
    il_env_mapping mapping;
    float rotation;      /* degrees about +y, counter-clockwise seen from above */
    float intensity;     /* multiplies the map; 0 means 1 */
} il_environment_desc;

/* ----------------------------------------------------------------- camera */

typedef struct il_camera_desc {
    il_vec3 position;
    il_vec3 target;      /* the point looked at */
    il_vec3 up;          /* zero means +y */
    float fov_y;         /* vertical field of view in degrees; 0 means 40 */
} il_camera_desc;

/* ------------------------------------------------------------------ scene */

typedef struct il_scene il_scene;

typedef struct il_mesh_desc {
    const char *name;            /* copied; may be NULL */
    uint32_t num_vertices;
    uint32_t num_triangles;
    const float *positions;      /* 3 floats per vertex, world space */
    const float *normals;        /* optional: 3 floats per vertex */
    const float *uvs;            /* optional: 2 floats per vertex */
    const uint32_t *indices;     /* 3 per triangle, counter-clockwise = front */
    uint32_t material;           /* index from il_scene_add_material; 0 is the
                                    scene's default grey diffuse (albedo 0.8) */
} il_mesh_desc;

typedef struct il_load_desc {
    il_log_fn log;               /* receives warnings while loading; may be NULL */
    void *log_user;
} il_load_desc;

typedef struct il_scene_info {
    uint32_t num_meshes;
    uint64_t num_triangles;
    uint32_t num_materials;      /* including the default material 0 */
    uint32_t num_textures;
    uint32_t num_lights;         /* point/spot/directional lights */
    uint64_t num_emissive_triangles;
    uint32_t num_panes;          /* meshes of a THIN_GLASS material (window panes) */
    bool has_environment;
    uint32_t num_portal_triangles; /* the environment's portals (il_scene_add_portal) */
    float portal_area;           /* their total area, m^2 */
    bool has_camera;             /* false until commit adds the default camera */
    il_vec3 bounds_min, bounds_max;
    uint64_t dropped_triangles;  /* NaN/Inf or degenerate, dropped on load */
    uint32_t num_warnings;
} il_scene_info;

/* An empty scene with one default material (index 0). */
il_status il_scene_create(il_scene **out, il_error *err);

/* Loads a file (any format assimp reads, or a .json scene file; see
 * docs/scene-format.md) or a built-in scene by name: "cornell", "atrium", the
 * radiosity rooms "simple-room", "shadow-room", "box-room", and the furnished
 * "office" (docs/builtin-scenes.md). */
il_status il_scene_load(const char *path_or_name, const il_load_desc *desc,
                        il_scene **out, il_error *err);

il_status il_scene_add_material(il_scene *scene, const il_material_desc *desc,
                                uint32_t *out_index, il_error *err);
/* Adds a texture of linear RGB floats (3 per texel, rows top to bottom).
 * Handles start at 1.  Values are clamped to [0, 1] (it multiplies an
 * albedo; a warning counts those above 1), NaN and Inf become 0. */
il_status il_scene_add_texture(il_scene *scene, uint32_t width, uint32_t height,
                               const float *rgb, uint32_t *out_handle, il_error *err);
/* Copies the mesh.  Triangles with NaN/Inf coordinates or zero area are
 * dropped and counted (il_scene_info.dropped_triangles). */
il_status il_scene_add_mesh(il_scene *scene, const il_mesh_desc *desc, il_error *err);
il_status il_scene_add_light(il_scene *scene, const il_light_desc *desc, il_error *err);
il_status il_scene_set_camera(il_scene *scene, const il_camera_desc *desc, il_error *err);
/* Gets the camera; returns false when the scene has none (before commit). */
bool il_scene_get_camera(const il_scene *scene, il_camera_desc *out);
il_status il_scene_set_environment(il_scene *scene, const il_environment_desc *desc,
                                   il_error *err);
/* Adds an environment portal: an opening (a window, a skylight) through
 * which the environment's light enters.  num_triangles triangles, their
 * corners corners[3t], corners[3t+1], corners[3t+2] counter-clockwise seen
 * from the side they light (inside the room).  From points on that side
 * most environment light samples are aimed through the portals, which
 * makes interiors lit by a sky far less noisy; the image converges to the
 * same values with or without them.  Not geometry: rays pass portals, and
 * a window's glass is a separate mesh.  Portals outlive a change of
 * environment.  Before commit; an error for a degenerate triangle
 * (docs/scene-format.md, "Portals"). */
il_status il_scene_add_portal(il_scene *scene, const il_vec3 *corners, uint32_t num_triangles,
                              il_error *err);

/* Validates the scene (an error when it has no triangle or no light), adds a
 * camera framing its bounds from +z when it has none (see docs/cli.md), builds
 * the ray-casting structure and the light tables.  Must be called before
 * rendering; the scene must not be changed afterwards. */
il_status il_scene_commit(il_scene *scene, il_error *err);
/* Before commit: removes the point, spot and directional lights and darkens
 * every emitter (their surfaces stay, as dark lamps); the environment stays,
 * and so does the sun il_scene_set_daylight added with it.  For a scene lit
 * by its sky alone (a daylight study). */
il_status il_scene_remove_lights(il_scene *scene, il_error *err);

/* Render settings a scene file asked for (the "render" block of a JSON scene,
 * docs/scene-format.md); a zero field or an empty method means "not set", so
 * the caller's own default or command-line option applies. */
typedef struct il_render_settings {
    uint32_t width, height;
    uint32_t spp;
    uint32_t max_depth;
    uint64_t seed;
    double time_limit;           /* seconds */
    char method[32];             /* e.g. "pt" */
} il_render_settings;

/* Gets the scene file's render settings; returns false (and zeroes `out`)
 * when it set none. */
bool il_scene_get_render_settings(const il_scene *scene, il_render_settings *out);

void il_scene_get_info(const il_scene *scene, il_scene_info *out);
/* The i-th warning recorded while loading, or NULL. */
const char *il_scene_warning(const il_scene *scene, uint32_t i);
void il_scene_release(il_scene *scene);

/* ------------------------------------------------------------ images, film */

/* A float RGB image, 3 floats per pixel, rows top to bottom. */
typedef struct il_image {
    uint32_t width, height;
    float *rgb;
} il_image;

typedef enum il_exr_precision { IL_EXR_HALF = 0, IL_EXR_FLOAT } il_exr_precision;
/* The largest magnitude a half EXR holds: larger values are written as it
 * (the sun's disc reaches about 2e6 W/(m^2 sr) at noon; IL_EXR_FLOAT keeps them). */
#define IL_EXR_HALF_MAX 65504.0f

/* Tone mapping: HDR radiance to display values (docs/tonemapping.md).  It
 * happens only at output: films and EXR/HDR/PFM files keep radiance. */
typedef enum il_tonemap_op {
    IL_TONEMAP_LINEAR = 0,   /* scale by the exposure, clamp, sRGB transfer */
    IL_TONEMAP_GAMMA,        /* scale, clamp, a plain power 1/gamma */
    IL_TONEMAP_REINHARD,     /* Reinhard et al. 2002 global operator with white point */
    IL_TONEMAP_FILMIC        /* ACES filmic curve (Narkowicz 2015 fit) */
} il_tonemap_op;

typedef struct il_tonemap_desc {
    il_tonemap_op op;
    float exposure;          /* EV: radiance times 2^exposure first (0 means none) */
    bool auto_exposure;      /* choose the exposure from the image: the Rec.709
                                luminance at auto_percentile (nearest rank, over
                                the pixels that are not black) maps to 1; this
                                multiplies with 2^exposure */
    float auto_percentile;   /* in (0, 100]; 0 means 99 (percent) */
    float gamma;             /* IL_TONEMAP_GAMMA: 0 means 2.2 */
    float white;             /* IL_TONEMAP_REINHARD: luminance (after exposure) that
                                maps to white; 0 means the image's largest */
    float bloom;             /* fraction of the light above bloom_threshold spread
                                into the glare; 0 means no bloom */
    float bloom_threshold;   /* luminance (after exposure) where bloom starts; 0 means 1 */
    float bloom_radius;      /* spread: the standard deviation of the glare's widest
                                Gaussian as a fraction of the image diagonal, up to
                                1; 0 means 0.02.  Bloom keeps each channel's total */
} il_tonemap_desc;

/* Maps an HDR image to display values in [0, 1] (after the transfer
 * function), into a newly allocated image (`out` may be `in`: its pixels are
 * replaced).  desc may be NULL (linear, EV 0).  A pixel with a NaN or
 * infinite channel becomes black, a negative channel 0.  Bad desc fields are
 * IL_ERR_INVALID. */
il_status il_tonemap(const il_image *in, const il_tonemap_desc *desc, il_image *out,
                     il_error *err);

typedef struct il_write_desc {
    float exposure;              /* PNG only: multiply by 2^exposure before the sRGB
                                    transfer (0 means none); ignored with tonemap */
    il_exr_precision exr_precision;
    const il_tonemap_desc *tonemap; /* PNG only: the operator; NULL means linear
                                       with exposure above */
} il_write_desc;

/* Resamples an environment map from one mapping to another (bilinear
 * lookups, supersampled); width is the output's width (0: about the same
 * texel density as the input).  Rotation is not applied. */
il_status il_envmap_convert(const il_image *src, il_env_mapping from, il_env_mapping to,
                            uint32_t width, il_image *dst, il_error *err);

/* Skies for daylight studies (docs/environment.md#skies), as lat-long
 * environment maps of width x width/2 texels, white, 683 lm/W:
 *
 * il_sky_overcast: the CIE standard overcast sky (Moon & Spencer 1942, CIE
 * 1955; the separate formula beside the general sky in CIE S 011/E:2003):
 * L(a) = Lz (1 + 2 sin a) / 3 at altitude a, with Lz set so that an
 * unobstructed horizontal surface receives horizontal_lux from the sky
 * (E = 7 pi Lz / 9).  For daylight-factor studies (docs/illuminance.md).
 *
 * il_sky_cie: the CIE standard general sky (CIE S 011/E:2003, ISO
 * 15469:2004), sky types 1 (overcast) to 15 (cloudless, turbid), for the
 * sun at (sun_altitude, sun_azimuth); each texel the mean of the standard's
 * relative luminance over its solid angle, scaled so that an unobstructed
 * horizontal surface receives horizontal_lux from the sky alone.  The sun's
 * own disc is not in the map: il_scene_set_daylight adds it as a
 * directional light.
 *
 * Below the horizon both have a diffuse ground of ground_albedo lit by the
 * sky and the sun: L = albedo (horizontal_lux + sun_normal_lux sin(sun
 * altitude)) / (683 pi), like the ground glow of Radiance's gensky.
 *
 * Directions in the scene: +y is up; north is -z and east +x, turned by
 * `north` degrees counter-clockwise seen from above (north = 90: north is
 * -x).  Azimuths are degrees clockwise from north seen from above (east
 * 90, south 180). */
typedef struct il_sky_desc {
    double horizontal_lux;   /* from the sky alone; 0 means 10,000 lx */
    double ground_albedo;    /* 0 to 1; negative means none (black ground); 0 means 0.2 */
    uint32_t width;          /* 0 means 256 (the sky is smooth: more texels only cost
                                cache misses when it is sampled); il_sky_cie needs a
                                multiple of 4 */
    int cie_type;            /* il_sky_cie: 1 to 15 (0 is the overcast sky above,
                                for il_scene_set_daylight) */
    double sun_altitude;     /* degrees above the horizon, more than 0 and at most 90 */
    double sun_azimuth;      /* degrees clockwise from north */
    double north;            /* degrees; see above */
    double sun_normal_lux;   /* the sun's illuminance on a surface facing it (0: no
                                direct sun); il_sun_normal_lux gives a model's value */
    double sun_diameter;     /* the sun's disc in degrees, up to 90, which softens
                                shadow edges: 0 means the sun's own 0.53, negative a
                                point (sharp shadows) */
} il_sky_desc;
il_status il_sky_overcast(const il_sky_desc *desc, il_image *out, il_error *err);
il_status il_sky_cie(const il_sky_desc *desc, il_image *out, il_error *err);

/* Sets the sky of desc (cie_type 0: the overcast sky; 1-15: il_sky_cie) as
 * the scene's environment and, when sun_normal_lux > 0, adds the sun as a
 * directional light of that illuminance (W/m^2 = lux / 683) shining from
 * (sun_altitude, sun_azimuth), a disc of sun_diameter.  The sun belongs to the sky: the next
 * il_scene_set_environment or il_scene_set_daylight removes it with the
 * sky, and il_scene_remove_lights leaves it.  The overcast sky has no sun:
 * a sun_normal_lux there is refused.  Before commit. */
il_status il_scene_set_daylight(il_scene *scene, const il_sky_desc *desc, il_error *err);
/* Whether the scene's environment is still the sky il_scene_set_daylight
 * set (a scene file's "environment": {"sky": ...} is set that way); *out,
 * when not NULL, gets that sky as set, horizontal_lux and ground_albedo's
 * defaults filled in. */
bool il_scene_get_daylight(const il_scene *scene, il_sky_desc *out);

/* Where the sun stands, seen from latitude and longitude (degrees, north and
 * east positive) at a moment given in seconds since 1970-01-01T00:00:00 UTC:
 * altitude in degrees above the horizon (refracted by a standard
 * atmosphere while above -1 degree), azimuth in degrees clockwise from
 * north.  The Astronomical Almanac's low-precision solar coordinates
 * (Michalsky 1988): about 0.01 degree from 1950 to 2050.  Moments outside
 * the years 1900-2100 are refused. */
il_status il_sun_position(double latitude, double longitude, double unix_seconds,
                          double *altitude, double *azimuth, il_error *err);

/* The direct normal illuminance of the sun for a CIE sky type at a solar
 * altitude (degrees), after the IES daylight-availability model (IES RP-21,
 * IES Lighting Handbook): E = 127,500 lx (1 + 0.034 cos(2 pi (J - 2) /
 * 365)) exp(-c / sin(altitude)), c = 0.21 for the clear types 11-15, 0.80
 * for the partly cloudy types 6-10; 0 for the overcast types 1-5 (and
 * type 0) and for a sun on or below the horizon.  day_of_year J is 1-366;
 * 0 leaves out the seasonal term. */
double il_sun_normal_lux(int cie_type, double sun_altitude, int day_of_year);

/* Reads PNG, JPEG (8-bit sRGB, decoded to linear), HDR (RGBE), EXR and PFM. */
il_status il_image_read(const char *path, il_image *out, il_error *err);
/* Writes by the file's extension: .exr .hdr .pfm .png.  The file is written to
 * a temporary name beside it and renamed, so a failed write leaves no file. */
il_status il_image_write(const il_image *image, const char *path,
                         const il_write_desc *desc, il_error *err);
il_status il_image_alloc(il_image *image, uint32_t width, uint32_t height, il_error *err);
void il_image_free(il_image *image);

typedef struct il_compare_result {
    double rmse;            /* root mean squared error over all channels */
    double rel_mse;         /* mean of (a-b)^2 / (b^2 + 0.01), b the reference */
    double mean_lum_a;      /* mean Rec.709 luminance */
    double mean_lum_b;
    double max_abs_error;   /* largest absolute channel difference */
} il_compare_result;

/* Compares A against reference B (same size); optionally fills `diff` with the
 * per-pixel absolute difference (allocated; free with il_image_free). */
il_status il_image_compare(const il_image *a, const il_image *b,
                           il_compare_result *out, il_image *diff, il_error *err);

/* The accumulation film every method renders into: per pixel a sum of
 * weighted radiance samples and a sum of weights. */
typedef struct il_film il_film;
il_status il_film_create(uint32_t width, uint32_t height, il_film **out, il_error *err);
uint32_t il_film_width(const il_film *film);
uint32_t il_film_height(const il_film *film);
void il_film_clear(il_film *film);
void il_film_add_sample(il_film *film, uint32_t x, uint32_t y, il_vec3 radiance, float weight);
/* The mean radiance per pixel, into a newly allocated image. */
il_status il_film_resolve(const il_film *film, il_image *out, il_error *err);
void il_film_release(il_film *film);

/* ------------------------------------------------------------------ render */

typedef enum il_method {
    IL_METHOD_PT = 0,        /* reference path tracer (docs/path-tracer.md) */
    IL_METHOD_RADIOSITY,     /* progressive-refinement radiosity (docs/radiosity.md) */
    IL_METHOD_HR,            /* hierarchical radiosity (docs/hierarchical-radiosity.md) */
    IL_METHOD_PHOTON,        /* photon mapping: global + caustic maps (docs/photon-mapping.md) */
    IL_METHOD_SPPM,          /* stochastic progressive photon mapping (docs/photon-mapping.md) */
    IL_METHOD_IBL,           /* environment map as many directional lights (docs/ibl.md) */
    IL_METHOD_LINESPACE,     /* Linespace light injection (docs/linespace.md) */
    IL_METHOD_RSM            /* reflective shadow maps with a shadow test (docs/rsm.md) */
} il_method;
typedef enum il_sampler_type { IL_SAMPLER_SOBOL = 0, IL_SAMPLER_PCG } il_sampler_type;
typedef enum il_filter_type { IL_FILTER_BOX = 0, IL_FILTER_GAUSSIAN } il_filter_type;

typedef struct il_render_progress {
    uint32_t passes_done;    /* samples per pixel completed so far (IL_METHOD_IBL:
                                lights so far; passes_total: all its lights) */
    uint32_t passes_total;   /* 0 when rendering for a time */
    double seconds;          /* since the render started */
    double time_limit;       /* 0 when rendering a sample count */
    uint64_t rays;           /* rays cast so far */
    const il_film *film;     /* complete after every pass: it may be written */
    double radius;           /* IL_METHOD_SPPM: the mean photon search radius (metres)
                                of the pixels that see a diffuse surface, after this
                                pass; 0 for the other methods */
} il_render_progress;

/* Called on the calling thread after every pass; return false to stop: il_render
 * then returns IL_OK and il_render_stats.spp says how many samples the film holds. */
typedef bool (*il_progress_fn)(const il_render_progress *progress, void *user);

/* ------------------------------------------------------------- radiosity */

typedef enum il_form_factor_method {
    IL_FF_AUTO = 0,          /* the hemicube while it has at least 4 pixels a patch
                                (up to 3N^2/4 patches at resolution N: 49,152 at the
                                default 256), ray-cast above (docs/radiosity.md) */
    IL_FF_HEMICUBE,          /* Cohen & Greenberg 1985: a z-buffered hemicube per patch */
    IL_FF_RAYCAST            /* cosine-distributed rays from the patch, through Embree */
} il_form_factor_method;

typedef enum il_radiosity_solver {
    IL_SOLVER_SHOOTING = 0,  /* progressive refinement (Cohen et al. 1988) */
    IL_SOLVER_JACOBI,        /* gathering sweeps, all patches from the previous sweep */
    IL_SOLVER_GAUSS_SEIDEL   /* gathering sweeps, updated in place */
} il_radiosity_solver;

/* Handed to il_radiosity_desc.on_step after every shot (or batch of shots)
 * and after every gathering sweep. */
typedef struct il_radiosity_progress {
    uint32_t step;             /* shots or sweeps done */
    uint32_t num_patches;
    double unshot_fraction;    /* unshot power / initial power (gathering: the
                                  power the last sweep added / initial power) */
    double seconds;            /* since the solve started */
    const float *radiance;     /* 3 floats per patch: current radiance, with the
                                  ambient term (Cohen et al. 1988) for display */
} il_radiosity_progress;

/* Return false to stop the solve early (the result so far is kept). */
typedef bool (*il_radiosity_step_fn)(const il_radiosity_progress *progress, void *user);

typedef struct il_radiosity_desc {
    float patch_size;          /* largest patch edge in metres; 0: automatic
                                  (about 4,000 patches over the scene) */
    uint32_t subdivisions;     /* > 0: uniform levels instead of patch_size; each
                                  splits every triangle or quad into 4 */
    il_form_factor_method form_factors;
    uint32_t hemicube_resolution; /* pixels along the top face; 0 means 256 */
    uint32_t ray_samples;      /* ray-cast rays per patch; 0 means 4096 */
    il_radiosity_solver solver;
    float tolerance;           /* stop when unshot/initial power is below; 0 means 0.01 */
    uint32_t max_steps;        /* most shots or sweeps; 0 means no limit but the tolerance */
    uint32_t ff_cache_mb;      /* memory for cached form-factor rows; 0 means 1024 */
    float adaptive_threshold;  /* > 0: after the first solve, split patches whose
                                  radiance differs from a neighbour's by more than
                                  this fraction, and solve again */
    il_radiosity_step_fn on_step;
    void *on_step_user;
} il_radiosity_desc;

/* What a radiosity solve measured (il_render_stats.radiosity). */
typedef struct il_radiosity_stats {
    uint32_t num_patches;
    uint32_t num_surfaces;
    uint32_t steps;            /* shots or sweeps */
    double unshot_fraction;    /* at the end */
    double view_fraction;      /* shooting, at the end: the largest unshot radiance
                                  over the mean radiance of what the camera sees
                                  (0: the camera sees no patch); the solve goes on
                                  until this too is under the tolerance */
    bool stalled;              /* the solve stopped because unshot_fraction no
                                  longer fell: light that cannot leave the
                                  scene (a closed room of albedo 1) has no
                                  finite solution (docs/radiosity.md) */
    il_form_factor_method form_factors; /* the back-end that computed the rows
                                  (IL_FF_AUTO resolved; the last solve's with
                                  adaptive subdivision) */
    double seconds_mesh;       /* meshing and its ray-casting structure */
    double seconds_form_factors; /* wall time spent computing form-factor rows */
    double seconds_solve;      /* the solve, form factors included */
    double seconds_render;     /* camera pass */
    uint64_t rows_computed;    /* form-factor rows computed (misses of the cache) */
    uint64_t cache_bytes;      /* memory held by cached rows at the end */
    uint64_t peak_bytes;       /* the solver's own largest allocation total */
} il_radiosity_stats;

/* --------------------------------------------------- hierarchical radiosity */

/* What the solve is doing when il_hr_desc.on_step is called. */
typedef enum il_hr_phase {
    IL_HR_LINKING = 0,         /* the initial links between facing patches */
    IL_HR_REFINING,            /* refinement (and its visibility rays) of
                                  iteration `iterations + 1` */
    IL_HR_ITERATED             /* an iteration's gather and push-pull are done */
} il_hr_phase;

/* Handed to il_hr_desc.on_step on the calling thread: about ten times a
 * second while the initial links are made and while links are refined, and
 * after every iteration. */
typedef struct il_hr_progress {
    il_hr_phase phase;
    uint32_t iterations;       /* iterations done (refine, then sweeps of gather
                                  and push-pull) */
    uint32_t roots_done;       /* LINKING, REFINING: patches whose links are made
                                  or refined in this phase so far */
    uint32_t num_roots;        /* input polygons (quadtree roots) */
    double energy_change;      /* ITERATED: the relative change of the reflected
                                  energy in this iteration (1 after the first) */
    double seconds;            /* since the solve started */
} il_hr_progress;

/* Return false to stop the solve early.  Asked after an iteration, the
 * solve ends with it.  Asked during a refinement after the first, the links
 * not yet refined stay as they are and the iteration's gather and push-pull
 * complete it.  Asked earlier (linking or the first refinement), no light
 * has been exchanged yet: the solution is the emission and the direct light
 * of point, spot, directional lights and sky.  il_hr_stats.stopped says so. */
typedef bool (*il_hr_step_fn)(const il_hr_progress *progress, void *user);

/* Hanrahan, Salzman & Aupperle 1991 as in SPLASH-2's radiosity program.  The
 * epsilons are relative, so rescaling the scene or its lights changes
 * nothing (docs/hierarchical-radiosity.md maps them to SPLASH-2's values). */
typedef struct il_hr_desc {
    float bf_eps;              /* refine a link while F * B * V / B_ref exceeds this,
                                  B_ref the scene's mean emitted radiance
                                  (sum A Le / sum A); 0 means 0.015 */
    float area_eps;            /* ... and the larger element's area exceeds this
                                  fraction of the scene's bounding-box diagonal
                                  squared; 0 means 2000 / 1700^2 (SPLASH-2's room) */
    float energy_eps;          /* stop when what is left of the reflected energy,
                                  estimated from its last two changes, falls
                                  below this fraction of it; 0 means 0.005 */
    uint32_t vis_rays;         /* visibility rays per link; 0 means 16 */
    uint32_t max_iterations;   /* refinements, each followed by gather +
                                  push-pull sweeps until the links' system
                                  meets energy_eps (at most 64); 0 means 100 */
    il_hr_step_fn on_step;     /* progress and stop; NULL: none (not called when
                                  the render is split across processes) */
    void *on_step_user;
} il_hr_desc;

typedef struct il_hr_stats {
    uint32_t patches;          /* input polygons (quadtree roots) */
    uint64_t elements;         /* all quadtree nodes */
    uint64_t leaves;
    uint64_t links;
    uint32_t iterations;       /* refinements, each followed by sweeps */
    uint32_t sweeps;           /* gather + push-pull sweeps, all iterations */
    uint64_t visibility_rays;
    double seconds_setup;      /* patches, initial links */
    double seconds_refine;     /* refinement + visibility, all iterations */
    double seconds_gather;     /* gather + push-pull, all iterations */
    double seconds_average;    /* per-vertex averaging and output mesh */
    double seconds_render;
    uint64_t peak_bytes;       /* pools of elements, links and visibility */
    bool stopped;              /* il_hr_desc.on_step asked the solve to stop */
    bool converged;            /* what is left fell below energy_eps (or
                                  there was no light to solve); false when
                                  max_iterations or a stop ended the solve */
    double energy_change;      /* the last iteration's relative change of the
                                  total energy (1 after the first) */
    bool stalled;              /* the solve stopped because its sweeps no longer
                                  converged: light that cannot leave the scene
                                  (a closed room of albedo 1) */
} il_hr_stats;

/* ---------------------------------------------------------- photon mapping */

/* How photons near a point are found: the k nearest in a balanced kd-tree
 * (within max_radius), or all within a fixed radius in a hashed uniform grid. */
typedef enum il_photon_lookup { IL_PHOTON_KDTREE = 0, IL_PHOTON_GRID } il_photon_lookup;
/* Density-estimation kernel (Jensen 2001, 7.2): cone filter (k = 1.1) or
 * Epanechnikov; both normalised so that a uniform density is unbiased. */
typedef enum il_photon_filter { IL_PHOTON_CONE = 0, IL_PHOTON_EPANECHNIKOV } il_photon_filter;

/* What IL_METHOD_PHOTON's set-up is doing when il_photon_desc.on_step is called. */
typedef enum il_photon_phase {
    IL_PHOTON_TRACING = 0,     /* photons leave the lights and are stored */
    IL_PHOTON_IRRADIANCE       /* irradiance precomputed at every 4th global photon */
} il_photon_phase;

typedef struct il_photon_progress {
    il_photon_phase phase;
    uint64_t done, total;      /* photons traced, or irradiance points computed, so far */
    double seconds;            /* since the set-up started */
} il_photon_progress;

/* Called on the calling thread during IL_METHOD_PHOTON's set-up, every few
 * tens of thousands of photons or points.  Return false to stop it early:
 * tracing ends with the photons traced so far (the first `done` indices,
 * the same photons as asking for that many, with their power scaled to
 * their number), and the precomputed irradiance is left out (every
 * Lambertian hit makes a full estimate, as with no_precomputed_irradiance).
 * The camera pass follows; il_photon_stats.stopped says so. */
typedef bool (*il_photon_step_fn)(const il_photon_progress *progress, void *user);

/* Jensen's two-pass photon mapping (IL_METHOD_PHOTON) and Hachisuka &
 * Jensen's stochastic progressive photon mapping (IL_METHOD_SPPM).  Radii
 * are fractions of the scene's size, so a scene in millimetres renders as
 * the same scene in metres: the bounding box's diagonal, or, where the
 * camera sees less than half of that, the diagonal of what it sees
 * (docs/photon-mapping.md, "Options"). */
typedef struct il_photon_desc {
    uint64_t photons;          /* PHOTON: photons emitted; 0 means 1,000,000.
                                  SPPM: photons emitted per pass; 0 means 250,000 */
    uint32_t k;                /* neighbours per kd-tree estimate; 0 means 100 */
    float max_radius;          /* largest search radius (kd-tree) or the fixed
                                  radius (grid); 0 means 0.02 */
    il_photon_lookup lookup;
    il_photon_filter filter;
    uint32_t final_gather;     /* PHOTON: rays per camera hit gathering indirect
                                  light from the global map at their hits; 0: the
                                  global map is read at the camera hit directly */
    float alpha;               /* SPPM: fraction of new photons kept per pass; 0 means 0.7 */
    float initial_radius;      /* SPPM: first per-pixel radius; 0 means 0.01 */
    uint32_t max_photon_depth; /* bounces a photon may take; 0 means max_depth - 1 */
    uint32_t no_precomputed_irradiance; /* PHOTON: 0 (default) reads the global map at
                                  Lambertian surfaces from irradiance precomputed at
                                  every 4th photon (Christensen 1999); nonzero: a
                                  full estimate at every hit */
    uint32_t no_portal_light;  /* 0 (default): in a scene with portals and light from
                                  outside, most photons start at the portals as the
                                  light coming in by them (docs/photon-mapping.md,
                                  "Windows"); nonzero: all leave the lights */
    /* Optional, for display (the viewer's photon points): called once the
     * photons are traced (PHOTON: the global map, which 0, then the caustic
     * map, which 1; SPPM: every pass, which 2) with their positions, 3
     * floats per photon, valid during the call only. */
    void (*on_photons)(const float *positions, size_t count, int which, void *user);
    void *on_photons_user;
    /* Optional, PHOTON: progress of the set-up, and a stop (il_photon_step_fn);
     * not called when the render is split across processes.  SPPM stops
     * between passes through il_render_desc.progress. */
    il_photon_step_fn on_step;
    void *on_step_user;
} il_photon_desc;

typedef struct il_photon_stats {
    uint64_t emitted;          /* photons emitted (all passes) */
    uint64_t stored_global;    /* photons in the global map (PHOTON) */
    uint64_t stored_caustic;   /* photons in the caustic map (PHOTON) */
    uint64_t stored;           /* photon hits deposited (SPPM, all passes) */
    uint64_t photon_rays;      /* rays cast tracing photons */
    uint32_t passes;           /* SPPM passes (PHOTON: 1) */
    double seconds_trace;      /* tracing and storing photons */
    double seconds_build;      /* building the kd-trees or grids */
    double seconds_render;     /* camera pass (estimates, final gather) */
    uint64_t map_bytes;        /* the photon maps and their search structures */
    uint32_t bytes_per_photon; /* one stored photon */
    bool stopped;              /* PHOTON: on_step stopped the set-up early */
} il_photon_stats;

/* ------------------------------------------------- many-light environment */

/* How IL_METHOD_IBL picks the directions of its lights from the map. */
typedef enum il_ibl_selection {
    IL_IBL_IMPORTANCE_SOBOL = 0, /* the map's importance distribution, Sobol points */
    IL_IBL_IMPORTANCE,       /* the map's importance distribution, random points */
    IL_IBL_SOBOL,            /* uniform over the sphere, Sobol points */
    IL_IBL_RANDOM            /* uniform over the sphere, random points */
} il_ibl_selection;

typedef enum il_ibl_shadows {
    IL_IBL_SHADOW_RAYS = 0,  /* exact: a shadow ray per light and pixel sample */
    IL_IBL_SHADOW_MAPS,      /* a shadow map per light, percentage-closer filtered */
    IL_IBL_SHADOW_NONE
} il_ibl_shadows;

/* Kemmer 2005: the environment becomes N directional lights of radiance /
 * pdf / N each, shading the first surface the camera sees (mirrors and
 * glass are followed to it, up to max_depth - 1 bounces).  The scene's
 * point, spot and directional lights and emitters light it too.  With
 * large N the image converges to the path tracer's with max_depth 1
 * (docs/ibl.md).  The scene needs an environment. */
typedef struct il_ibl_desc {
    uint32_t lights;           /* N, at most 2^24; 0 means 1024 */
    il_ibl_selection selection;
    il_ibl_shadows shadows;
    uint32_t batch;            /* lights added per progressive step; the film is
                                  complete after each; 0 means 64 */
    uint32_t shadow_map_size;  /* texels per side, at most 8192; 0 means 512 */
    float shadow_bias;         /* fraction of the scene's diagonal, at most 1;
                                  0 means 0.001 */
    uint32_t pcf_taps;         /* percentage-closer filter width in texels (odd,
                                  at most 15); 0 means 3 */
} il_ibl_desc;

typedef struct il_ibl_stats {
    uint32_t lights;           /* lights in the film (fewer than asked for when
                                  stopped by the time limit or the callback) */
    uint64_t shadow_rays;      /* of the environment's lights (the other lights'
                                  are in il_render_stats.rays) */
    double seconds_lights;     /* building the light set (and the shadow maps) */
    double seconds_shade;      /* camera samples and shading */
} il_ibl_stats;

/* -------------------------------------------------- reflective shadow maps */

/* Dachsbacher & Stamminger 2005, "Reflective Shadow Maps", as in Nilles 2017
 * (IL_METHOD_RSM, docs/rsm.md).  Every spot light gets a map of the surfaces
 * it lights directly, ray cast through a perspective grid of texels (a spot
 * wider than 60 degrees and a point light: six cube faces; a directional
 * light: one orthographic map over the scene), holding per texel the world
 * position, normal, area and reflected flux.  The first non-specular surface
 * a camera ray reaches takes direct light as the path tracer does, and one
 * bounce of indirect light from the texels, each a small Lambertian emitter.
 * Area lights and the environment light directly only. */
typedef struct il_rsm_desc {
    uint32_t resolution;     /* texels per side of each map, 1 to 4096; 0 means 512 */
    uint32_t samples;        /* texels gathered per shading point and map, 1 to
                                65536; 0 means 400 (Dachsbacher & Stamminger) */
    float radius;            /* r_max: radius of the sampling disk around the
                                point's projection, as a fraction of the map's
                                side, up to 2; 0 means 1.5, which covers the
                                whole map (unbiased); smaller is the paper's
                                faster, biased choice */
    bool all_texels;         /* gather every texel of every map (the exact sum;
                                samples and radius are ignored) */
    uint32_t maps;           /* maps gathered per shading point when the scene has
                                more (a point light has six): chosen at random, half
                                in proportion to their reflected flux and half
                                uniformly, each weighted by 1 / (maps x its
                                probability): an unbiased estimate of the sum over
                                every map; 1 to 4096, 0 means 8 */
    bool all_maps;           /* gather every map at every shading point */
    bool shadow_test;        /* Nilles 2017 eq. 11: a shadow ray between the
                                shading point and every texel gathered */
} il_rsm_desc;

typedef struct il_rsm_stats {
    uint32_t maps;           /* faces rendered (one per spot, six per point light) */
    uint32_t maps_per_point; /* maps gathered per shading point (all: `maps`) */
    uint32_t resolution;     /* texels per side */
    uint64_t texels;         /* texels that hold reflected flux, all maps */
    uint64_t map_bytes;
    uint64_t gathered;       /* texel contributions evaluated */
    uint64_t shadow_rays;    /* of the shadow test */
    double seconds_build;    /* ray casting the maps */
    double seconds_gather;   /* the camera pass with the gathering */
} il_rsm_stats;

/* ------------------------------------------------------------- linespace */

/* Nilles 2017 light injection into a grid of Linespaces (Keul et al. 2016),
 * IL_METHOD_LINESPACE, docs/linespace.md.  Light paths from every light
 * leave, along each segment after their first hit, flux x length in the
 * shaft (pair of boundary patches) and direction of every voxel they cross;
 * a path tracer reads that back as radiance at its diffuse hits instead of
 * tracing on.  Sizes are fractions of a voxel, so the options are scale-free. */
/* Handed to il_linespace_desc.on_step during the light injection. */
typedef struct il_linespace_progress {
    uint64_t injected, total;  /* light paths injected so far, of all */
    double seconds;            /* since the injection started */
} il_linespace_progress;

/* Called on the calling thread after every round of light paths (some tens
 * of thousands).  Return false to stop the injection: the Linespace then
 * holds the paths injected so far, the first `injected` indices, the same
 * as asking for that many (il_linespace_stats.inject_rays counts them and
 * .stopped says so), and the camera pass follows. */
typedef bool (*il_linespace_step_fn)(const il_linespace_progress *progress, void *user);

typedef struct il_linespace_desc {
    uint32_t grid;             /* voxels along the scene's longest side (the others
                                  in proportion, voxels near cubic), 1 to 256; 0 means 8 */
    uint32_t n;                /* N: patches per face side (15 N^4 shafts per voxel),
                                  1 to 8; 0 means 4 */
    uint64_t inject_rays;      /* light paths injected, at most 10^10; 0 means 1,000,000 */
    uint32_t inject_depth;     /* bounces a light path takes; 0 means max_depth - 1 */
    float blur;                /* radius of the disk the lookup point is jittered on,
                                  as a fraction of the voxel's smallest side, at most 4;
                                  0 means none */
    bool no_occlusion_test;    /* skip the in-shaft occlusion test (on by default) */
    bool no_fallback;          /* no entry traces on: an occluded one gives no light
                                  too (by default an occluded entry traces on) */
    bool fallback_empty;       /* an empty entry (no deposit) traces on too (the
                                  thesis's fallback variant); off by default: it
                                  reads as no light, which is unbiased and faster
                                  (docs/linespace.md, "Fallback") */
    bool no_solid_angle;       /* normalise every shaft as if all subtended the same
                                  solid angle (the thesis's reading; grid patterns) */
    bool coarse;               /* build a coarser level too (N / its smallest prime
                                  factor patches per side; N > 1) and read it where
                                  an entry got too few deposits, before falling back
                                  to tracing (off by default: docs/linespace.md) */
    uint32_t coarse_below;     /* too few: below this many, 1 to 255 (1: only empty
                                  entries); 0 means 32 */
    bool trace_first_bounce;   /* trace one bounce from the first diffuse or glossy
                                  hit and read the Linespace at the next one (off by
                                  default: slower samples, less bias; docs/linespace.md) */
    float glossy_n1;           /* Phong exponents below n1 read the Linespace; 0 means 10 */
    float glossy_n2;           /* above n2 trace on; in between blend; 0 means 100 */
    bool no_portal_light;      /* false (default): in a scene with portals and light
                                  from outside, most light paths start at the portals
                                  and the grid covers the interior the camera sees
                                  (docs/linespace.md, "Windows"); true: the grid over
                                  the whole scene, all paths from the lights */
    il_linespace_step_fn on_step; /* progress and stop of the injection; NULL: none
                                  (not called when split across processes) */
    void *on_step_user;
} il_linespace_desc;

typedef struct il_linespace_stats {
    uint32_t grid[3];          /* voxels per axis */
    float grid_min[3], grid_max[3]; /* the grid's box */
    bool interior;             /* it covers the interior the camera sees, not the
                                  whole scene (no_portal_light) */
    uint64_t outside;          /* camera path vertices outside it (or, with the portals'
                                  light, outside by a portal), which traced on */
    uint32_t n;
    uint64_t voxels;           /* voxels holding a Linespace (non-empty) */
    uint64_t shafts;           /* shafts stored (those containing geometry) */
    uint64_t candidates;       /* candidate triangle references of all stored shafts */
    uint64_t overflow_shafts;  /* shafts whose occlusion test casts a ray instead */
    uint64_t memory_bytes;     /* the whole structure */
    uint64_t inject_rays;      /* light paths emitted (fewer than asked when stopped) */
    uint64_t injected_segments; /* (segment, voxel) deposits */
    uint64_t lookups, lookup_hits, lookup_empty, lookup_occluded; /* occluded: the in-shaft
                                  test found geometry first (tested: every stored entry
                                  by default, those holding light with fallback_empty
                                  or no_fallback) */
    uint64_t lookup_coarse;    /* of lookup_hits, those read from the coarse level */
    double seconds_build;      /* grid, shafts and candidate lists */
    double seconds_inject;
    double seconds_sample;     /* the camera pass */
    bool stopped;              /* on_step stopped the injection early */
} il_linespace_stats;

/* ------------------------------------------------- distributed rendering */

/* One render split across processes (docs/distributed.md; the CLI's
 * `mpirun -np N illum render` implements this with MPI).  Every process
 * loads the same scene and calls il_render with the same options and a
 * distrib naming its own rank; IL_METHOD_PHOTON, IL_METHOD_SPPM and
 * IL_METHOD_RADIOSITY then split their work (photon index ranges, kd-tree
 * subtrees, image tiles or pixel rows, form-factor rows) and exchange
 * results through `allgather`, which every process calls the same number
 * of times in the same order.  The film each process gets back is its share: the films of
 * all processes summed (il_film_data) are il_render's single-process film
 * bit for bit.  il_render_stats.rays, nonfinite_samples, photon.photon_rays
 * and radiosity.rows_computed count this process's work only.  Progress
 * and on_step callbacks are not called (a process that stopped alone would
 * leave the others waiting) and a time limit is IL_ERR_INVALID.  Other
 * methods ignore distrib.  NULL (or size 1): a single process. */
typedef struct il_distrib {
    int rank, size;            /* 0 <= rank < size */
    /* Concatenates every process's `bytes` bytes in rank order into *out
     * (malloc'd, the library frees it; NULL when all sent nothing) and sets
     * counts[r] (size entries) to process r's bytes.  Returns 0 on success;
     * non-zero fails the render. */
    int (*allgather)(void *user, const void *data, size_t bytes, void **out, size_t *counts);
    void *user;
    /* Optional, dynamic load balancing of the camera pass's tiles: adds
     * `count` to a counter shared by all processes (0 at the start of the
     * render) and returns its value before, the first of the tiles this
     * process then renders; a fast process claims more often.  Called only
     * from the thread that called il_render, at most once per render's
     * camera pass per claim.  NULL: the tiles are dealt statically (tile t
     * to process t mod size). */
    uint64_t (*claim)(void *user, uint64_t count);
} il_distrib;

typedef struct il_render_desc {
    il_method method;
    uint32_t spp;            /* samples per pixel; 0 means 16, or unlimited when
                                time_limit is set (IL_METHOD_IBL: camera samples,
                                each shaded by every light; 0 means 1, and the time
                                limit bounds the lights instead) */
    double time_limit;       /* seconds; 0 means none */
    uint32_t max_depth;      /* most bounces (scattering events) on a path; 1 is
                                direct lighting only; 0 means 8 */
    uint64_t seed;
    int threads;             /* 0 means all cores */
    il_sampler_type sampler;
    il_filter_type filter;
    il_progress_fn progress;
    void *progress_user;
    const il_radiosity_desc *radiosity; /* IL_METHOD_RADIOSITY options; NULL: defaults */
    const il_hr_desc *hr;    /* IL_METHOD_HR options; NULL: defaults */
    const il_photon_desc *photon; /* IL_METHOD_PHOTON and IL_METHOD_SPPM options; NULL: defaults */
    const il_ibl_desc *ibl;  /* IL_METHOD_IBL options; NULL: defaults */
    const il_rsm_desc *rsm;  /* IL_METHOD_RSM options; NULL: defaults */
    const il_linespace_desc *linespace; /* IL_METHOD_LINESPACE options; NULL: defaults */
    const il_distrib *distrib; /* one render across processes (see il_distrib); NULL: this one */
} il_render_desc;

typedef struct il_render_stats {
    uint32_t spp;            /* samples per pixel rendered */
    uint64_t rays;           /* all rays cast, camera + bounce + shadow */
    double seconds;
    uint64_t nonfinite_samples; /* samples dropped because they were NaN or Inf */
    il_radiosity_stats radiosity; /* IL_METHOD_RADIOSITY only */
    il_hr_stats hr;          /* IL_METHOD_HR only */
    il_photon_stats photon;  /* IL_METHOD_PHOTON and IL_METHOD_SPPM only */
    il_ibl_stats ibl;        /* IL_METHOD_IBL only */
    il_rsm_stats rsm;        /* IL_METHOD_RSM only */
    il_linespace_stats linespace; /* IL_METHOD_LINESPACE only */
} il_render_stats;

/* Renders the committed scene through its camera into the film (which is
 * cleared first).  The same seed gives a bit-identical film whatever the
 * thread count. */
il_status il_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                    il_render_stats *stats, il_error *err);

/* A render split into pieces (docs/distributed.md): the pixels [x0,x1) x [y0,y1). */
typedef struct il_render_rect {
    uint32_t x0, y0, x1, y1;
} il_render_rect;

/* The path tracer (desc->method IL_METHOD_PT, desc->time_limit 0) on one
 * region: adds samples 0..spp-1 of its pixels to the film, which is NOT
 * cleared; other pixels are untouched.  Each pixel gets the very sums
 * il_render gives it, so regions rendered apart into cleared films and added
 * (il_film_data) give il_render's film bit for bit.  No progress calls. */
il_status il_render_region(const il_scene *scene, il_film *film, const il_render_desc *desc,
                           const il_render_rect *region, il_render_stats *stats,
                           il_error *err);

/* The film's accumulation buffer, to move films between processes: per pixel,
 * row by row, 4 doubles: sum w*r, sum w*g, sum w*b, sum w. */
double *il_film_data(il_film *film);

/* ------------------------------------------------------------ illuminance */

/* What a light meter would read (docs/illuminance.md): the irradiance at a
 * point on a surface of the given orientation, from every light of the scene
 * and their interreflections, estimated by the path tracer's paths.  A
 * sensor is virtual: it blocks no light, and one on a surface reads that
 * surface's irradiance. */
typedef struct il_sensor {
    il_vec3 position;
    il_vec3 normal;          /* the side it faces; need not be unit, must not be zero */
} il_sensor;

typedef struct il_illuminance_desc {
    uint32_t samples;        /* paths per sensor; 0 means 1024 */
    uint32_t max_depth;      /* as il_render_desc.max_depth, counting the sensor as the
                                first bounce: 1 is direct light only; 0 means 8 */
    uint64_t seed;
    int threads;             /* 0 means all cores */
    il_sampler_type sampler;
    /* Called on the calling thread after every round of samples (fraction done
     * in [0, 1]); return false to stop: the readings then rest on the samples
     * taken so far (the same number for every sensor, il_illuminance_stats.samples). */
    bool (*progress)(double fraction, double seconds, void *user);
    void *progress_user;
} il_illuminance_desc;

/* One sensor's reading. */
typedef struct il_illuminance {
    il_vec3 irradiance;      /* W/m^2, linear Rec.709 */
    float lux;               /* illuminance: 683 lm/W times the luminance of irradiance */
    float lux_error;         /* the standard error of lux over the sensor's samples
                                (Monte Carlo noise; quasi-random samples do better) */
} il_illuminance;

typedef struct il_illuminance_stats {
    uint32_t samples;        /* paths per sensor taken (fewer when progress stopped it) */
    uint64_t rays;
    double seconds;
    uint64_t nonfinite_samples; /* samples dropped because they were NaN or Inf */
} il_illuminance_stats;

/* Reads `count` sensors into out[0..count-1].  The same seed gives the same
 * readings, bit for bit, whatever the thread count.  stats may be NULL. */
il_status il_measure_illuminance(const il_scene *scene, const il_sensor *sensors, size_t count,
                                 const il_illuminance_desc *desc, il_illuminance *out,
                                 il_illuminance_stats *stats, il_error *err);

/* Hours of direct sun (docs/illuminance.md#sun-hours): for each sensor, how
 * long, within the period from `start` lasting `hours`, the sun's centre
 * stands above min_altitude, in front of the sensor (on the side its normal
 * faces) and unhidden by the scene, as seen from latitude and longitude
 * (il_sun_position, north turned as in il_sky_desc).  The period is cut into
 * steps of step_minutes, each counted whole when the sun is seen at its
 * middle.  No weather: a cloudless day, as the sunlight-exposure checks of
 * EN 17037 and BR 209 assume.  The scene need not be committed nor have a
 * light. */
typedef struct il_sun_hours_desc {
    double latitude, longitude; /* degrees, north and east positive */
    double start;            /* seconds since 1970-01-01T00:00Z (il_parse_moment's) */
    double hours;            /* length of the period, up to a year; 0 means 24 */
    double step_minutes;     /* 0 means 1; at most 60 */
    double min_altitude;     /* degrees, 0 to 90: the sun counts only above it */
    double north;            /* degrees, as il_sky_desc.north */
    int threads;             /* 0 means all cores */
    /* Called on the calling thread after every hundredth or so of the sun's
     * places, or every million rays or so when that comes first (fraction
     * done in [0, 1)); return false to stop: the hours are then those of the
     * period up to the last step done (hours_done). */
    bool (*progress)(double fraction, double seconds, void *user);
    void *progress_user;
} il_sun_hours_desc;

typedef struct il_sun_hours_stats {
    double sun_up_hours;     /* hours of the period the sun stood above min_altitude:
                                what a sensor facing it with nothing around gets */
    double hours_done;       /* the period's hours counted: all of it unless stopped */
    bool stopped;            /* progress stopped it */
    uint64_t rays;
    double seconds;
} il_sun_hours_stats;

/* hours[i]: sensor i's hours of sun.  Deterministic.  stats may be NULL. */
il_status il_sun_hours(const il_scene *scene, const il_sensor *sensors, size_t count,
                       const il_sun_hours_desc *desc, double *hours, il_sun_hours_stats *stats,
                       il_error *err);

/* The sensors the scene's camera sees in a width x height image (a false-colour
 * illuminance view): for each pixel, row by row from the top, the surface
 * point at the centre of its view, facing the camera (the shading normal,
 * turned to the camera's side; a window pane, thin_glass, is looked through).
 * seen[i] is false, and sensors[i] zero, where the pixel sees no surface. */
il_status il_camera_sensors(const il_scene *scene, uint32_t width, uint32_t height,
                            il_sensor *sensors, bool *seen, il_error *err);

/* Sensors spread over named surfaces: the triangles of every mesh whose name,
 * or whose material's name, contains desc->name (case-insensitive), about one
 * sensor per spacing^2 of area (a triangle too small for one of its own gets
 * one as the area adds up), each on the front of its triangle (the geometric
 * normal, turned to the side of the vertex normals).  With desc->facing not
 * zero, only triangles whose normal is within 45 degrees of it.  Writes up to
 * `capacity` sensors into out (may be NULL to count them) and fills *info.
 * IL_ERR_INVALID, naming the scene's meshes, when nothing matches. */
typedef struct il_surface_sensor_desc {
    const char *name;        /* part of a mesh or material name; "" or NULL: all */
    il_vec3 facing;          /* zero: any orientation */
    float spacing;           /* metres between sensors; 0 means 0.1 */
} il_surface_sensor_desc;

typedef struct il_surface_sensor_info {
    size_t count;            /* sensors placed (all of them, even beyond capacity) */
    uint64_t triangles;      /* triangles that matched */
    double area;             /* their area, m^2 */
} il_surface_sensor_info;

il_status il_surface_sensors(const il_scene *scene, const il_surface_sensor_desc *desc,
                             il_sensor *out, size_t capacity, il_surface_sensor_info *info,
                             il_error *err);

/* ------------------------------------------------------------------- bake */

/* Light written onto the geometry: the scene's meshes as the method meshed
 * them (a diffuse method's patches), with the outgoing radiance at every
 * vertex.  Surfaces that are not diffuse (mirror, glass) keep their
 * triangles with zero radiance. */
typedef struct il_bake_mesh {
    char name[64];
    uint32_t num_vertices;
    uint32_t num_triangles;
    float *positions;          /* 3 per vertex */
    float *normals;            /* 3 per vertex */
    float *radiance;           /* 3 per vertex: W/(sr m^2), linear Rec.709 */
    uint32_t *indices;         /* 3 per triangle */
    uint32_t material;         /* the scene material */
    uint32_t *patches;         /* 1 per triangle: the patch it belongs to (hr: the
                                  element, a leaf), numbered across the whole bake;
                                  UINT32_MAX on mirror/glass triangles (no patch).
                                  A quad patch is 2 triangles: its outline is the
                                  edges not shared within one patch (the viewer's
                                  patch boundaries). */
} il_bake_mesh;

typedef struct il_bake_result {
    uint32_t num_meshes;
    il_bake_mesh *meshes;
    il_render_stats stats;
} il_bake_result;

/* Solves the scene with desc->method (IL_METHOD_RADIOSITY or IL_METHOD_HR; others give
 * IL_ERR_INVALID until they can bake) and returns per-vertex radiance. */
il_status il_bake(const il_scene *scene, const il_render_desc *desc, il_bake_result **out,
                  il_error *err);

/* il_bake that shows the solve converging (the interactive viewer): after
 * every solver step (radiosity: when il_radiosity_desc.on_step would be
 * called, which is still called; hr: after every iteration but the last)
 * on_step gets the solution so far as per-vertex meshes, like il_bake's,
 * valid during the call only (current->stats is not filled).  Return false
 * to stop the solve early; *out then holds the solution so far.  on_step
 * NULL: il_bake. */
typedef bool (*il_bake_step_fn)(const il_bake_result *current, void *user);
il_status il_bake_progressive(const il_scene *scene, const il_render_desc *desc,
                              il_bake_step_fn on_step, void *user, il_bake_result **out,
                              il_error *err);

typedef struct il_bake_write_desc {
    float exposure;            /* 8-bit colours: radiance * 2^exposure, clamped, sRGB */
} il_bake_write_desc;

/* Writes by extension: .ply (binary: positions, normals, 8-bit sRGB colours
 * and the float radiance as properties radiance_r/g/b) or .glb/.gltf (through
 * assimp; COLOR_0 display colours, COLOR_1 float radiance).  Written to a
 * temporary name and renamed.  desc may be NULL. */
il_status il_bake_write(const il_bake_result *bake, const char *path,
                        const il_bake_write_desc *desc, il_error *err);
void il_bake_release(il_bake_result *bake);

#ifdef __cplusplus
}
#endif
#endif /* ILLUM_H */
