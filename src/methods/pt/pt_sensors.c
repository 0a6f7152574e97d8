/* Where sensors go (illum.h): on the surfaces a camera sees
 * (il_camera_sensors) and spread over named surfaces (il_surface_sensors),
 * for il_measure_illuminance (pt_illuminance.c). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "core/error.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/trace.h"

static bool is_pane(const il_scene *scene, uint32_t mesh)
{
    return scene->materials[scene->meshes[mesh].material].type == IL_MATERIAL_THIN_GLASS;
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
            /* A window pane is looked through: the sensor goes on what lies
             * behind it (the ray caster lets most rays through, this all). */
            for (int k = 0; k < 16 && seen[i] && is_pane(scene, hit.mesh); k++) {
                il_vec3 p = v3_fma(ray.org, ray.dir, hit.t);
                il_vec3 ng = v3_normalize(hit.ng);
                ray.org = il_offset_origin(scene->tracer, p, ng, ray.dir);
                seen[i] = il_trace_closest(scene->tracer, &ray, &hit);
            }
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
            if (oriented) {
                il_surface c;
                il_scene_surface(scene, mi, t, 1.0f / 3.0f, 1.0f / 3.0f, &c);
                if (v3_dot(c.ng, facing) < 0.70710678f)
                    continue;
            }
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
