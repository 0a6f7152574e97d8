/* Building the in-memory scene: il_scene_create / add_* / commit / release. */
#include "scene/scene.h"
#include "scene/pane.h"
#include "scene/portal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "image/envmap.h"
#include "scene/lights.h"
#include "trace/trace.h"

/* Grows a dynamic array to hold at least `need` elements. */
static bool grow(void **items, uint32_t *cap, uint32_t need, size_t elem, il_error *err)
{
    if (need <= *cap)
        return true;
    uint32_t ncap = *cap ? *cap * 2 : 8;
    while (ncap < need)
        ncap *= 2;
    void *p = realloc(*items, (size_t)ncap * elem);
    if (!p) {
        il_fail(err, IL_ERR_MEMORY, "out of memory growing the scene");
        return false;
    }
    *items = p;
    *cap = ncap;
    return true;
}

static void copy_name(char dst[IL_NAME_MAX], const char *src, const char *fallback)
{
    snprintf(dst, IL_NAME_MAX, "%s", src && src[0] ? src : fallback);
}

il_status il_scene_create(il_scene **out, il_error *err)
{
    *out = NULL;
    il_scene *s = il_calloc(1, sizeof *s, err);
    if (!s)
        return IL_ERR_MEMORY;
    s->environment_light = IL_NO_LIGHT;
    il_material_desc def = {.name = "default", .diffuse = {0.8f, 0.8f, 0.8f}};
    uint32_t idx;
    il_status st = il_scene_add_material(s, &def, &idx, err);
    if (st != IL_OK) {
        il_scene_release(s);
        return st;
    }
    *out = s;
    return IL_OK;
}

void il_scene_warn(il_scene *s, const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (s->log)
        s->log(IL_LOG_WARNING, buf, s->log_user);
    if (grow((void **)&s->warnings, &s->cap_warnings, s->num_warnings + 1, sizeof(char *), NULL)) {
        char *copy = strdup(buf);
        if (copy)
            s->warnings[s->num_warnings++] = copy;
    }
}

static bool vec_finite_nonneg(il_vec3 v) { return v3_is_finite(v) && v.x >= 0 && v.y >= 0 && v.z >= 0; }

/* A surface cannot reflect more light than it receives: an albedo or tint
 * above 1 creates energy at every bounce, so the path tracer's image grows
 * with max-depth and the radiosity solvers never converge.  Such channels
 * are clamped to 1 (docs/materials.md). */
static il_vec3 clamp_albedo(il_vec3 c, bool *clamped)
{
    il_vec3 r = v3_min(c, v3s(1.0f));
    *clamped |= !(r.x == c.x && r.y == c.y && r.z == c.z);
    return r;
}

/* A point with a coordinate beyond ±10^15 scene units is treated like a NaN
 * one (docs/scene-format.md): Embree takes no ray whose origin or direction
 * has a component above about 1.8e18 (it aborts the program on one), and a
 * shadow ray's direction is the difference of two points. */
#define IL_MAX_COORD 1e15f

static bool point_in_range(il_vec3 p)
{
    return v3_is_finite(p) && fabsf(p.x) <= IL_MAX_COORD && fabsf(p.y) <= IL_MAX_COORD &&
           fabsf(p.z) <= IL_MAX_COORD;
}

/* A thin pane's checks: neutral (its shadow rays pass a grey fraction of
 * the light, scene/pane.h), an index above 1, a transmittance it can reach;
 * *tau the internal transmittance that gives it. */
static il_status pane_params(const il_material_desc *d, const char *name, float *tau, il_error *err)
{
    il_vec3 c = d->specular;
    if (!v3_is_zero(c) && !(c.x == c.y && c.y == c.z && c.x >= 1.0f))
        return il_fail(err, IL_ERR_INVALID, "material '%s': a thin_glass pane is neutral (its tint "
                       "must be white or left out); use transmittance to darken it", name);
    float ior = d->ior > 0.0f ? d->ior : 1.5f;
    if (!(ior > 1.0f))
        return il_fail(err, IL_ERR_INVALID, "material '%s': a thin_glass pane needs an ior above 1 "
                       "(got %g)", name, (double)ior);
    float t = d->transmittance, clear = il_pane_clear_transmittance(ior);
    if (!(t >= 0.0f) || !(t <= clear))
        return il_fail(err, IL_ERR_INVALID, "material '%s': transmittance %g is outside 0 to %.4f "
                       "(clear glass of ior %g; 0 means clear)", name, (double)t, (double)clear,
                       (double)ior);
    *tau = t > 0.0f ? il_pane_tau_for(ior, t) : 1.0f;
    return IL_OK;
}

il_status il_scene_add_material(il_scene *s, const il_material_desc *d, uint32_t *out_index,
                                il_error *err)
{
    if (s->committed)
        return il_fail(err, IL_ERR_INVALID, "the scene is committed and can no longer change");
    const char *name = d->name ? d->name : "";
    if (!vec_finite_nonneg(d->diffuse) || !vec_finite_nonneg(d->specular) ||
        !vec_finite_nonneg(d->emission))
        return il_fail(err, IL_ERR_INVALID, "material '%s': colours must be finite and >= 0", name);
    if ((unsigned)d->type > IL_MATERIAL_THIN_GLASS)
        return il_fail(err, IL_ERR_INVALID, "material '%s': unknown type %d", name, (int)d->type);
    if (d->diffuse_texture > s->num_textures)
        return il_fail(err, IL_ERR_INVALID, "material '%s': no texture %u", name, d->diffuse_texture);
    if (!(d->exponent >= 0.0f) || !isfinite(d->exponent) || !(d->ior >= 0.0f) || !isfinite(d->ior))
        return il_fail(err, IL_ERR_INVALID, "material '%s': exponent and ior must be finite and >= 0",
                       name);
    float pane_tau = 1.0f;
    if (d->type == IL_MATERIAL_THIN_GLASS) {
        il_status st = pane_params(d, name, &pane_tau, err);
        if (st != IL_OK)
            return st;
    }
    if (!grow((void **)&s->materials, &s->cap_materials, s->num_materials + 1, sizeof(il_material), err))
        return IL_ERR_MEMORY;
    il_material *m = &s->materials[s->num_materials];
    memset(m, 0, sizeof *m);
    copy_name(m->name, d->name, "unnamed");
    m->type = d->type;
    bool clamped = false;
    m->diffuse = clamp_albedo(d->diffuse, &clamped);
    m->diffuse_texture = d->diffuse_texture;
    m->specular = clamp_albedo(d->specular, &clamped);
    if (clamped)
        il_scene_warn(s, "material '%s': albedo above 1 clamped to 1 (a surface cannot reflect "
                         "more light than it receives)", m->name);
    if (IL_MATERIAL_IS_DELTA(d->type) && v3_is_zero(m->specular))
        m->specular = v3s(1.0f);
    m->exponent = d->exponent > 0.0f ? d->exponent : 32.0f;
    m->ior = d->ior > 0.0f ? d->ior : 1.5f;
    m->pane_tau = pane_tau;
    m->emission = d->emission;
    m->two_sided = d->two_sided;
    if (out_index)
        *out_index = s->num_materials;
    s->num_materials++;
    return IL_OK;
}

il_status il_scene_add_texture(il_scene *s, uint32_t w, uint32_t h, const float *rgb,
                               uint32_t *out_handle, il_error *err)
{
    if (s->committed)
        return il_fail(err, IL_ERR_INVALID, "the scene is committed and can no longer change");
    if (w == 0 || h == 0 || !rgb)
        return il_fail(err, IL_ERR_INVALID, "texture has no pixels (%ux%u)", w, h);
    if (!grow((void **)&s->textures, &s->cap_textures, s->num_textures + 1, sizeof(il_texture), err))
        return IL_ERR_MEMORY;
    size_t n = (size_t)w * h * 3;
    float *copy = il_malloc(n * sizeof(float), err);
    if (!copy)
        return IL_ERR_MEMORY;
    /* A texture multiplies a diffuse albedo: values outside [0, 1] (HDR
     * images, NaN) are clamped, as a material's albedo is. */
    size_t above = 0;
    for (size_t i = 0; i < n; i++) {
        above += isfinite(rgb[i]) && rgb[i] > 1.0f;
        copy[i] = isfinite(rgb[i]) && rgb[i] > 0.0f ? il_minf(rgb[i], 1.0f) : 0.0f;
    }
    if (above)
        il_scene_warn(s, "texture %u (%ux%u): %zu values above 1 clamped to 1 (a texture "
                         "multiplies an albedo)", s->num_textures + 1, w, h, above);
    s->textures[s->num_textures] = (il_texture){w, h, copy};
    s->num_textures++;
    if (out_handle)
        *out_handle = s->num_textures; /* handles start at 1 */
    return IL_OK;
}

static bool triangle_ok(const float *pos, const uint32_t *tri, uint32_t nv)
{
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv)
        return false;
    il_vec3 p[3];
    for (int k = 0; k < 3; k++) {
        const float *q = pos + 3 * (size_t)tri[k];
        p[k] = v3(q[0], q[1], q[2]);
        if (!point_in_range(p[k]))
            return false;
    }
    il_vec3 c = v3_cross(v3_sub(p[1], p[0]), v3_sub(p[2], p[0]));
    /* Degenerate: zero area relative to the edge lengths (a sliver or a line). */
    float area2 = v3_length(c);
    float edge2 = fmaxf(v3_length2(v3_sub(p[1], p[0])), v3_length2(v3_sub(p[2], p[0])));
    return area2 > 1e-12f * edge2 && area2 > 0.0f && isfinite(area2);
}

il_status il_scene_add_mesh(il_scene *s, const il_mesh_desc *d, il_error *err)
{
    if (s->committed)
        return il_fail(err, IL_ERR_INVALID, "the scene is committed and can no longer change");
    const char *name = d->name ? d->name : "unnamed";
    if (d->num_triangles > 0 && (!d->positions || !d->indices))
        return il_fail(err, IL_ERR_INVALID, "mesh '%s': positions and indices are required", name);
    if (d->material >= s->num_materials)
        return il_fail(err, IL_ERR_INVALID, "mesh '%s': no material %u", name, d->material);

    /* Keep only valid triangles. */
    uint32_t *keep = il_malloc((size_t)d->num_triangles * 3 * sizeof(uint32_t), err);
    if (!keep)
        return IL_ERR_MEMORY;
    uint32_t nt = 0;
    for (uint32_t t = 0; t < d->num_triangles; t++) {
        const uint32_t *tri = d->indices + 3 * (size_t)t;
        if (triangle_ok(d->positions, tri, d->num_vertices)) {
            memcpy(keep + 3 * (size_t)nt, tri, 3 * sizeof(uint32_t));
            nt++;
        }
    }
    uint32_t dropped = d->num_triangles - nt;
    if (dropped) {
        s->dropped_triangles += dropped;
        il_scene_warn(s, "mesh '%s': dropped %u of %u triangles (NaN/Inf or out-of-range "
                         "coordinates, bad indices or zero area)", name, dropped, d->num_triangles);
    }
    if (nt == 0) {
        free(keep);
        return IL_OK;
    }

    if (!grow((void **)&s->meshes, &s->cap_meshes, s->num_meshes + 1, sizeof(il_mesh), err)) {
        free(keep);
        return IL_ERR_MEMORY;
    }
    il_mesh *m = &s->meshes[s->num_meshes];
    memset(m, 0, sizeof *m);
    copy_name(m->name, d->name, "unnamed");
    m->num_vertices = d->num_vertices;
    m->num_triangles = nt;
    m->material = d->material;
    m->indices = keep;
    /* One spare element: Embree may read 16 bytes at the last vertex. */
    m->positions = il_calloc((size_t)d->num_vertices + 1, sizeof(il_vec3), err);
    if (!m->positions) {
        free(keep);
        return IL_ERR_MEMORY;
    }
    for (uint32_t v = 0; v < d->num_vertices; v++) {
        il_vec3 p = v3(d->positions[3 * v], d->positions[3 * v + 1], d->positions[3 * v + 2]);
        /* Vertices used only by dropped triangles may be non-finite or out
         * of range: zero them so bounds stay finite. */
        m->positions[v] = point_in_range(p) ? p : v3s(0.0f);
    }
    if (d->normals) {
        m->normals = il_malloc((size_t)d->num_vertices * sizeof(il_vec3), err);
        if (!m->normals) {
            free(keep);
            free(m->positions);
            return IL_ERR_MEMORY;
        }
        for (uint32_t v = 0; v < d->num_vertices; v++) {
            il_vec3 n = v3(d->normals[3 * v], d->normals[3 * v + 1], d->normals[3 * v + 2]);
            float l = v3_length(n);
            m->normals[v] = (isfinite(l) && l > 0.0f) ? v3_scale(n, 1.0f / l) : v3s(0.0f);
        }
    }
    if (d->uvs) {
        m->uvs = il_malloc((size_t)d->num_vertices * sizeof(il_vec2), err);
        if (!m->uvs) {
            free(keep);
            free(m->positions);
            free(m->normals);
            return IL_ERR_MEMORY;
        }
        for (uint32_t v = 0; v < d->num_vertices; v++) {
            il_vec2 uv = v2(d->uvs[2 * v], d->uvs[2 * v + 1]);
            m->uvs[v] = (isfinite(uv.x) && isfinite(uv.y)) ? uv : v2(0.0f, 0.0f);
        }
    }
    s->num_meshes++;
    return IL_OK;
}

il_status il_scene_add_light(il_scene *s, const il_light_desc *d, il_error *err)
{
    if (s->committed)
        return il_fail(err, IL_ERR_INVALID, "the scene is committed and can no longer change");
    if ((unsigned)d->type > IL_LIGHT_DIRECTIONAL)
        return il_fail(err, IL_ERR_INVALID, "light: unknown type %d", (int)d->type);
    if (!v3_is_finite(d->position) || !v3_is_finite(d->direction) || !vec_finite_nonneg(d->intensity))
        return il_fail(err, IL_ERR_INVALID, "light: position, direction and intensity must be "
                                            "finite (intensity >= 0)");
    /* Beyond this a light's power (4 pi I, or I times the scene's disk)
     * overflows a float and the light would silently be left out. */
    if (v3_max_comp(d->intensity) > 1e30f)
        return il_fail(err, IL_ERR_INVALID, "light: intensity %g is out of range (at most 1e30)",
                       (double)v3_max_comp(d->intensity));
    if (!point_in_range(d->position))
        return il_fail(err, IL_ERR_INVALID, "light: position (%g, %g, %g) is out of range "
                       "(coordinates within +-1e15)", (double)d->position.x, (double)d->position.y,
                       (double)d->position.z);
    if (!(d->spot_angle >= 0.0f && d->spot_angle <= 180.0f) || !(d->spot_exponent >= 0.0f) ||
        !isfinite(d->spot_exponent))
        return il_fail(err, IL_ERR_INVALID, "spot light: angle must be in [0, 180] degrees and the "
                                            "exponent >= 0");
    if (!(d->diameter >= 0.0f && d->diameter <= 90.0f))
        return il_fail(err, IL_ERR_INVALID, "directional light: the disc's diameter must be in [0, 90] degrees");
    if (d->diameter > 0.0f && d->type != IL_LIGHT_DIRECTIONAL)
        return il_fail(err, IL_ERR_INVALID, "light: only a directional light has a diameter");
    if (!grow((void **)&s->user_lights, &s->cap_user_lights, s->num_user_lights + 1,
              sizeof(il_light_desc), err))
        return IL_ERR_MEMORY;
    s->user_lights[s->num_user_lights++] = *d;
    return IL_OK;
}

il_status il_scene_remove_lights(il_scene *s, il_error *err)
{
    if (!s)
        return il_fail(err, IL_ERR_INVALID, "remove lights: no scene");
    if (s->committed)
        return il_fail(err, IL_ERR_INVALID, "the scene is committed and can no longer change");
    /* The sun of il_scene_set_daylight belongs to the sky and stays. */
    if (s->has_sky_sun) {
        s->user_lights[0] = s->user_lights[s->sky_sun];
        s->sky_sun = 0;
    }
    s->num_user_lights = s->has_sky_sun ? 1u : 0u;
    for (uint32_t i = 0; i < s->num_materials; i++)
        s->materials[i].emission = v3s(0.0f);
    return IL_OK;
}

il_status il_scene_set_camera(il_scene *s, const il_camera_desc *d, il_error *err)
{
    if (!v3_is_finite(d->position) || !v3_is_finite(d->target) || !v3_is_finite(d->up))
        return il_fail(err, IL_ERR_INVALID, "camera: position, target and up must be finite");
    if (!point_in_range(d->position) || !point_in_range(d->target))
        return il_fail(err, IL_ERR_INVALID, "camera: position and target must lie within +-1e15");
    if (!(d->fov_y >= 0.0f && d->fov_y < 180.0f))
        return il_fail(err, IL_ERR_INVALID, "camera: fov %g must be in (0, 180) degrees",
                       (double)d->fov_y);
    il_camera_desc c = *d;
    if (v3_is_zero(c.up))
        c.up = v3(0, 1, 0);
    if (c.fov_y == 0.0f)
        c.fov_y = 40.0f;
    il_vec3 fwd = v3_sub(c.target, c.position);
    if (v3_length(fwd) <= 0.0f)
        return il_fail(err, IL_ERR_INVALID, "camera: target equals position");
    if (v3_length(v3_cross(v3_normalize(fwd), v3_normalize(c.up))) < 1e-6f)
        return il_fail(err, IL_ERR_INVALID, "camera: up is parallel to the view direction");
    s->camera.desc = c;
    s->camera.present = true;
    return IL_OK;
}

bool il_scene_get_camera(const il_scene *s, il_camera_desc *out)
{
    if (!s->camera.present)
        return false;
    *out = s->camera.desc;
    return true;
}

static void free_envmap(il_scene *s)
{
    if (s->envmap) {
        il_envmap_free(s->envmap);
        free(s->envmap);
        s->envmap = NULL;
    }
}

/* A map is copied (times its intensity) and its sampling tables are built
 * here, so that commit and rendering find them ready (image/envmap.h). */
/* A new environment replaces the old one's sun too (il_scene_set_daylight). */
/* The sky il_scene_set_daylight set is being replaced: its sun goes too. */
static void drop_daylight(il_scene *s)
{
    s->has_daylight = false;
    if (!s->has_sky_sun)
        return;
    memmove(&s->user_lights[s->sky_sun], &s->user_lights[s->sky_sun + 1],
            sizeof(il_light_desc) * (s->num_user_lights - s->sky_sun - 1));
    s->num_user_lights--;
    s->has_sky_sun = false;
}

il_status il_scene_set_environment(il_scene *s, const il_environment_desc *d, il_error *err)
{
    if (s->committed)
        return il_fail(err, IL_ERR_INVALID, "the scene is committed and can no longer change");
    if (!d)
        return il_fail(err, IL_ERR_INVALID, "environment: no description given");
    if (!vec_finite_nonneg(d->radiance))
        return il_fail(err, IL_ERR_INVALID, "environment: radiance must be finite and >= 0");
    if (!d->map) {
        free_envmap(s);
        drop_daylight(s);
        s->environment = *d;
        s->has_environment = !v3_is_zero(d->radiance);
        return IL_OK;
    }
    if ((unsigned)d->mapping > IL_ENV_CROSS)
        return il_fail(err, IL_ERR_INVALID, "environment: unknown mapping %d", (int)d->mapping);
    il_envmap *env = il_calloc(1, sizeof *env, err);
    if (!env)
        return IL_ERR_MEMORY;
    uint64_t clamped = 0;
    il_status st = il_envmap_init(env, d->map, d->mapping, d->rotation, d->intensity, &clamped, err);
    if (st != IL_OK) {
        free(env);
        return st;
    }
    free_envmap(s);
    drop_daylight(s);
    s->envmap = env;
    s->environment = *d;
    s->environment.map = NULL;
    s->environment.radiance = env->dist.mean;
    s->has_environment = !v3_is_zero(env->dist.mean);
    if (clamped)
        il_scene_warn(s, "environment map: %llu negative texel values set to 0",
                      (unsigned long long)clamped);
    if (!s->has_environment)
        il_scene_warn(s, "environment map: every texel is black; the map gives no light");
    return IL_OK;
}

static void compute_bounds(il_scene *s)
{
    il_vec3 lo = v3s(INFINITY), hi = v3s(-INFINITY);
    for (uint32_t i = 0; i < s->num_meshes; i++) {
        const il_mesh *m = &s->meshes[i];
        for (uint32_t t = 0; t < 3 * m->num_triangles; t++) {
            il_vec3 p = m->positions[m->indices[t]];
            lo = v3_min(lo, p);
            hi = v3_max(hi, p);
        }
    }
    s->bounds_min = lo;
    s->bounds_max = hi;
    s->scene_center = v3_scale(v3_add(lo, hi), 0.5f);
    s->scene_radius = fmaxf(0.5f * v3_length(v3_sub(hi, lo)), 1e-6f);
}

/* A scene without a camera is framed from +z: looking down -z at the centre
 * of its bounds, from far enough that the bounding sphere fits the vertical
 * field of view (40 degrees).  Documented in docs/cli.md. */
static void add_default_camera(il_scene *s)
{
    const float fov = 40.0f;
    float half = 0.5f * fov * IL_PI / 180.0f;
    float dist = s->scene_radius / sinf(half);
    il_camera_desc c = {
        .position = v3(s->scene_center.x, s->scene_center.y, s->scene_center.z + dist),
        .target = s->scene_center,
        .up = v3(0, 1, 0),
        .fov_y = fov,
    };
    s->camera.desc = c;
    s->camera.present = true;
}

/* The record of triangle t of mesh m (see il_tri_geom). */
static void tri_geom_compute(const il_mesh *m, uint32_t t, il_tri_geom *g)
{
    const uint32_t *tri = m->indices + 3 * (size_t)t;
    g->v[0] = tri[0];
    g->v[1] = tri[1];
    g->v[2] = tri[2];
    g->pad = 0;
    g->p0 = m->positions[tri[0]];
    g->p1 = m->positions[tri[1]];
    g->p2 = m->positions[tri[2]];
    g->ng = v3_normalize(v3_cross(v3_sub(g->p1, g->p0), v3_sub(g->p2, g->p0)));
}

static void free_tri_geom(il_scene *s)
{
    for (uint32_t i = 0; i < s->num_meshes; i++) {
        free(s->meshes[i].geom);
        s->meshes[i].geom = NULL;
    }
}

/* Fills every mesh's il_tri_geom records, aligned to cache lines. */
static il_status build_tri_geom(il_scene *s, il_error *err)
{
    free_tri_geom(s);
    for (uint32_t i = 0; i < s->num_meshes; i++) {
        il_mesh *m = &s->meshes[i];
        size_t bytes = (size_t)m->num_triangles * sizeof(il_tri_geom);
        m->geom = aligned_alloc(64, bytes ? bytes : 64);
        if (!m->geom) {
            free_tri_geom(s);
            return il_fail(err, IL_ERR_MEMORY, "out of memory for the triangle table");
        }
        for (uint32_t t = 0; t < m->num_triangles; t++)
            tri_geom_compute(m, t, &m->geom[t]);
    }
    return IL_OK;
}

il_status il_scene_commit(il_scene *s, il_error *err)
{
    if (s->committed)
        return IL_OK;
    uint64_t tris = 0;
    for (uint32_t i = 0; i < s->num_meshes; i++)
        tris += s->meshes[i].num_triangles;
    if (tris == 0)
        return il_fail(err, IL_ERR_INVALID, "the scene is empty: it has no valid triangle");
    compute_bounds(s);
    if (!s->camera.present)
        add_default_camera(s);
    il_status st = build_tri_geom(s, err);
    if (st != IL_OK)
        return st;
    st = il_lights_build(s, err);
    if (st != IL_OK) {
        free_tri_geom(s);
        return st;
    }
    st = il_tracer_create(s, &s->tracer, err);
    if (st != IL_OK) {
        il_lights_free(s);
        free_tri_geom(s);
        return st;
    }
    s->committed = true;
    return IL_OK;
}

void il_scene_get_info(const il_scene *s, il_scene_info *o)
{
    memset(o, 0, sizeof *o);
    o->num_meshes = s->num_meshes;
    o->num_materials = s->num_materials;
    o->num_textures = s->num_textures;
    o->num_lights = s->num_user_lights;
    o->has_environment = s->has_environment;
    o->num_portal_triangles = s->num_portals;
    for (uint32_t i = 0; i < s->num_portals; i++)
        o->portal_area += s->portals[i].area;
    o->has_camera = s->camera.present;
    o->dropped_triangles = s->dropped_triangles;
    o->num_warnings = s->num_warnings;
    il_vec3 lo = v3s(INFINITY), hi = v3s(-INFINITY);
    for (uint32_t i = 0; i < s->num_meshes; i++) {
        const il_mesh *m = &s->meshes[i];
        o->num_triangles += m->num_triangles;
        if (!v3_is_zero(s->materials[m->material].emission))
            o->num_emissive_triangles += m->num_triangles;
        o->num_panes += s->materials[m->material].type == IL_MATERIAL_THIN_GLASS;
        for (uint32_t t = 0; t < 3 * m->num_triangles; t++) {
            il_vec3 p = m->positions[m->indices[t]];
            lo = v3_min(lo, p);
            hi = v3_max(hi, p);
        }
    }
    if (o->num_triangles == 0)
        lo = hi = v3s(0.0f);
    o->bounds_min = lo;
    o->bounds_max = hi;
}

const char *il_scene_warning(const il_scene *s, uint32_t i)
{
    return i < s->num_warnings ? s->warnings[i] : NULL;
}

void il_scene_release(il_scene *s)
{
    if (!s)
        return;
    il_tracer_release(s->tracer);
    il_lights_free(s);
    for (uint32_t i = 0; i < s->num_meshes; i++) {
        free(s->meshes[i].positions);
        free(s->meshes[i].normals);
        free(s->meshes[i].uvs);
        free(s->meshes[i].indices);
        free(s->meshes[i].geom);
    }
    free(s->meshes);
    free(s->materials);
    for (uint32_t i = 0; i < s->num_textures; i++)
        free(s->textures[i].rgb);
    free(s->textures);
    free(s->user_lights);
    free(s->portals);
    free_envmap(s);
    for (uint32_t i = 0; i < s->num_warnings; i++)
        free(s->warnings[i]);
    free(s->warnings);
    free(s);
}

/* ------------------------------------------------------------ surface query */

il_vec3 il_texture_sample(const il_texture *tex, il_vec2 uv)
{
    /* Bilinear with wrapping; v=0 is the bottom row (OpenGL/glTF flip handled by loaders). */
    float x = (uv.x - floorf(uv.x)) * (float)tex->width - 0.5f;
    float y = (1.0f - (uv.y - floorf(uv.y))) * (float)tex->height - 0.5f;
    float fx = floorf(x), fy = floorf(y);
    float tx = x - fx, ty = y - fy;
    int x0 = (int)fx, y0 = (int)fy;
    il_vec3 acc = v3s(0.0f);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int xi = ((x0 + i) % (int)tex->width + (int)tex->width) % (int)tex->width;
            int yi = ((y0 + j) % (int)tex->height + (int)tex->height) % (int)tex->height;
            const float *px = tex->rgb + 3 * ((size_t)yi * tex->width + (size_t)xi);
            float w = (i ? tx : 1.0f - tx) * (j ? ty : 1.0f - ty);
            acc = v3_fma(acc, v3(px[0], px[1], px[2]), w);
        }
    return acc;
}

il_vec3 il_material_diffuse(const il_scene *s, const il_material *m, il_vec2 uv)
{
    if (m->diffuse_texture == 0)
        return m->diffuse;
    return v3_mul(m->diffuse, il_texture_sample(&s->textures[m->diffuse_texture - 1], uv));
}

/* The triangle's record: precomputed after il_scene_commit, else computed
 * into *tmp the same way. */
static inline const il_tri_geom *tri_geom(const il_mesh *m, uint32_t prim, il_tri_geom *tmp)
{
    if (m->geom)
        return &m->geom[prim];
    tri_geom_compute(m, prim, tmp);
    return tmp;
}

/* The point, the geometric normal and the shading normal at barycentrics
 * (b1, b2), shared by il_scene_surface and il_scene_point. */
static inline void point_normals(const il_mesh *m, const il_tri_geom *g, float b1, float b2,
                                 float b0, il_vec3 *p, il_vec3 *ng, il_vec3 *ns)
{
    *p = v3_add(v3_add(v3_scale(g->p0, b0), v3_scale(g->p1, b1)), v3_scale(g->p2, b2));
    *ng = g->ng;
    *ns = g->ng;
    if (m->normals) {
        il_vec3 n = v3_add(v3_add(v3_scale(m->normals[g->v[0]], b0), v3_scale(m->normals[g->v[1]], b1)),
                           v3_scale(m->normals[g->v[2]], b2));
        float l = v3_length(n);
        if (l > 1e-6f && isfinite(l)) {
            /* Authored normals say which side is the front (as in pbrt-v4):
             * the geometric normal is turned to their side. */
            *ns = v3_scale(n, 1.0f / l);
            if (v3_dot(*ns, *ng) < 0.0f)
                *ng = v3_neg(*ng);
        }
    }
}

void il_scene_surface(const il_scene *s, uint32_t mesh, uint32_t prim, float b1, float b2,
                      il_surface *out)
{
    const il_mesh *m = &s->meshes[mesh];
    il_tri_geom tmp;
    const il_tri_geom *g = tri_geom(m, prim, &tmp);
    float b0 = 1.0f - b1 - b2;
    point_normals(m, g, b1, b2, b0, &out->p, &out->ng, &out->ns);
    out->uv = v2(0.0f, 0.0f);
    if (m->uvs) {
        il_vec2 a = m->uvs[g->v[0]], b = m->uvs[g->v[1]], c = m->uvs[g->v[2]];
        out->uv = v2(a.x * b0 + b.x * b1 + c.x * b2, a.y * b0 + b.y * b1 + c.y * b2);
    }
    out->mesh = mesh;
    out->prim = prim;
    out->material = &s->materials[m->material];
}

void il_scene_point(const il_scene *s, uint32_t mesh, uint32_t prim, float b1, float b2,
                    il_vec3 *p, il_vec3 *ng)
{
    const il_mesh *m = &s->meshes[mesh];
    il_tri_geom tmp;
    il_vec3 ns;
    point_normals(m, tri_geom(m, prim, &tmp), b1, b2, 1.0f - b1 - b2, p, ng, &ns);
}
