/* Packing a scene for kernel/kernel_path.h; see kernel_scene.h. */
#include "kernel/kernel_scene.h"

#include <stdlib.h>
#include <string.h>
#include "core/error.h"
#include "image/envmap.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/trace.h"

static ilk_vec3 to_k(il_vec3 v) { return ilk_v3(v.x, v.y, v.z); }

/* What the kernels cannot render yet, refused with a clear message: the
 * photon kernels (extended false) know untextured diffuse surfaces and
 * emissive triangles, the path kernel (extended true) also Phong, mirror
 * and glass surfaces, diffuse textures, delta lights and a sky, uniform or
 * a map. */
static il_status check_supported(const il_scene *scene, bool extended, il_error *err)
{
    for (uint32_t i = 0; i < scene->num_materials; i++) {
        const il_material *m = &scene->materials[i];
        if (!extended && m->diffuse_texture)
            return il_fail(err, IL_ERR_INVALID, "material '%s': textured materials do not run on the GPU "
                           "photon kernels yet (docs/cuda.md)", m->name);
        if (m->type == IL_MATERIAL_THIN_GLASS)
            return il_fail(err, IL_ERR_INVALID, "material '%s': thin_glass panes do not run on the GPU "
                           "yet; render with --device cpu (docs/cuda.md)", m->name);
        if (!extended && m->type != IL_MATERIAL_DIFFUSE)
            return il_fail(err, IL_ERR_INVALID, "material '%s': only untextured diffuse materials run on "
                           "the GPU photon kernels so far (docs/cuda.md)", m->name);
    }
    if (scene->num_discs > ILK_MAX_DISCS)
        return il_fail(err, IL_ERR_INVALID, "%u directional lights with a disc: the GPU shows at most %u; "
                       "render with --device cpu (docs/cuda.md)", scene->num_discs, ILK_MAX_DISCS);
    if (!extended && (scene->num_user_lights || scene->has_environment))
        return il_fail(err, IL_ERR_INVALID, "only emissive triangles light a GPU render so far "
                       "(no point, spot or directional lights, no environment; docs/cuda.md)");
    return IL_OK;
}

/* Materials as il_bsdf_init resolves them: colours clamped at zero, a
 * Phong's kd + ks scaled down to at most 1 per channel (Lafortune &
 * Willems 1994, section 3), its lobe chosen by the albedos' luminance.  A
 * textured material keeps its own colour and its clamped ks, for
 * ilk_material_at to resolve with the texel at each hit. */
static void pack_material(const il_material *m, ilk_material *k)
{
    memset(k, 0, sizeof *k);
    il_vec3 kd = v3_max(m->diffuse, v3s(0.0f)), ks = v3_max(m->specular, v3s(0.0f));
    k->type = m->type == IL_MATERIAL_MIRROR       ? ILK_MATERIAL_MIRROR
              : m->type == IL_MATERIAL_DIELECTRIC ? ILK_MATERIAL_DIELECTRIC
                                                  : ILK_MATERIAL_DIFFUSE;
    k->diffuse_prob = 1.0f;
    k->exponent = m->exponent > 0.0f ? m->exponent : 32.0f;
    k->ior = m->ior > 0.0f ? m->ior : 1.5f;
    k->specular = to_k(ks);    /* mirror, glass: the tint (scene.c made zero white) */
    if (m->type == IL_MATERIAL_PHONG) {
        k->type = ILK_MATERIAL_PHONG;
        float peak = v3_max_comp(v3_add(kd, ks));
        if (peak > 1.0f) {
            kd = v3_scale(kd, 1.0f / peak);
            ks = v3_scale(ks, 1.0f / peak);
        }
        float ld = il_luminance(kd), ls = il_luminance(ks);
        k->diffuse_prob = ld + ls > 0.0f ? ld / (ld + ls) : 1.0f;
        k->specular = to_k(ks);
    }
    k->diffuse = to_k(kd);
    k->emission = to_k(m->emission);
    k->two_sided = m->two_sided;
    k->texture = m->diffuse_texture;
    if (k->texture) {
        k->diffuse = to_k(m->diffuse);
        k->specular = to_k(v3_max(m->specular, v3s(0.0f)));
    }
}

/* The textures' texels end to end, and the texture coordinates of every
 * triangle in leaf order, when a material has a texture. */
static il_status pack_textures(const il_scene *scene, il_kscene *out, il_error *err)
{
    bool any = false;
    for (uint32_t i = 0; i < scene->num_materials; i++)
        any = any || scene->materials[i].diffuse_texture != 0;
    if (!any || out->bvh.num_tris == 0)
        return IL_OK;
    uint64_t floats = 0;
    for (uint32_t i = 0; i < scene->num_textures; i++)
        floats += 3ull * scene->textures[i].width * scene->textures[i].height;
    out->textures = il_calloc(scene->num_textures, sizeof *out->textures, err);
    out->texels = il_malloc(sizeof *out->texels * (floats ? floats : 1), err);
    out->uvs = il_calloc(out->bvh.num_tris, sizeof *out->uvs, err);
    if (!out->textures || !out->texels || !out->uvs)
        return IL_ERR_MEMORY;
    out->num_textures = scene->num_textures;
    out->num_texels = floats;
    out->num_uvs = out->bvh.num_tris;
    uint64_t at = 0;
    for (uint32_t i = 0; i < scene->num_textures; i++) {
        const il_texture *t = &scene->textures[i];
        uint64_t n = 3ull * t->width * t->height;
        out->textures[i] = (ilk_texture){t->width, t->height, at};
        memcpy(out->texels + at, t->rgb, sizeof(float) * n);
        at += n;
    }
    for (uint32_t i = 0; i < out->bvh.num_tris; i++) {
        const ilk_tri *t = &out->bvh.tris[i];
        const il_mesh *m = &scene->meshes[t->mesh];
        if (!m->uvs)
            continue;
        const uint32_t *ix = m->indices + 3 * (size_t)t->prim;
        for (int k = 0; k < 3; k++) {
            out->uvs[i].u[k] = m->uvs[ix[k]].x;
            out->uvs[i].v[k] = m->uvs[ix[k]].y;
        }
    }
    return IL_OK;
}

/* The vertex normals of every triangle in leaf order, or none when no mesh
 * has normals. */
static il_status pack_normals(const il_scene *scene, il_kscene *out, il_error *err)
{
    bool any = false;
    for (uint32_t i = 0; i < scene->num_meshes; i++)
        any = any || scene->meshes[i].normals != NULL;
    if (!any || out->bvh.num_tris == 0)
        return IL_OK;
    out->normals = il_calloc(out->bvh.num_tris, sizeof *out->normals, err);
    if (!out->normals)
        return IL_ERR_MEMORY;
    out->num_normals = out->bvh.num_tris;
    for (uint32_t i = 0; i < out->bvh.num_tris; i++) {
        const ilk_tri *t = &out->bvh.tris[i];
        const il_mesh *m = &scene->meshes[t->mesh];
        if (!m->normals)
            continue;
        const uint32_t *ix = m->indices + 3 * (size_t)t->prim;
        for (int k = 0; k < 3; k++)
            out->normals[i].n[k] = to_k(m->normals[ix[k]]);
    }
    return IL_OK;
}

/* The map's importance-sampling table (il_envmap_dist) as the kernel's
 * flat CDFs: the rows' marginal, then each row's conditional. */
static il_status pack_env_cdf(const il_envmap_dist *d, il_kscene *out, il_error *err)
{
    uint32_t W = d->width, H = d->height;
    out->num_env_cdf = (H + 1) + (uint64_t)H * (W + 1);
    out->env_cdf = il_malloc(sizeof(float) * out->num_env_cdf, err);
    if (!out->env_cdf)
        return IL_ERR_MEMORY;
    out->env_grid_w = W;
    out->env_grid_h = H;
    memcpy(out->env_cdf, d->marginal.cdf, sizeof(float) * (H + 1));
    for (uint32_t j = 0; j < H; j++)
        memcpy(out->env_cdf + (H + 1) + (uint64_t)j * (W + 1), d->rows[j].cdf, sizeof(float) * (W + 1));
    return IL_OK;
}

/* The environment map as a latitude-longitude map in its own frame (the
 * rotation stays with the kernel): a latitude-longitude map as it is, an
 * angular or cross map resampled by the CPU's own bilinear lookup at the
 * texel centres of one twice as wide as tall and twice as tall as the
 * probe (or as four cross faces): at the probe's own height the
 * resampling's blur moved the image's mean by 0.7% on test_kernel_path's
 * 16x16 probe, at twice it by 0.3%.  With its sampling table. */
static il_status pack_envmap(const il_scene *scene, il_kscene *out, il_error *err)
{
    const il_envmap *env = scene->envmap;
    if (!scene->has_environment || !env)
        return IL_OK;
    const il_image *img = &env->img;
    bool latlong = env->mapping == IL_ENV_LATLONG;
    uint32_t h = latlong ? img->height : env->mapping == IL_ENV_ANGULAR ? 2 * img->height : 4 * (img->width / 3);
    uint32_t w = latlong ? img->width : 2 * h;
    if (w == 0 || h == 0)
        return IL_OK;
    il_status st = pack_env_cdf(&env->dist, out, err);
    if (st != IL_OK)
        return st;
    out->env_texels = il_malloc(sizeof(float) * 3 * (size_t)w * h, err);
    if (!out->env_texels)
        return IL_ERR_MEMORY;
    out->env_width = w;
    out->env_height = h;
    if (latlong) {
        memcpy(out->env_texels, img->rgb, sizeof(float) * 3 * (size_t)w * h);
        return IL_OK;
    }
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            il_vec3 d = il_envmap_latlong_dir(((float)x + 0.5f) / (float)w, ((float)y + 0.5f) / (float)h);
            il_vec3 L = il_envmap_lookup(img, env->mapping, d);
            float *t = out->env_texels + 3 * ((size_t)y * w + x);
            t[0] = L.x, t[1] = L.y, t[2] = L.z;
        }
    return IL_OK;
}

/* cdf[0..n] of the weights w (uniform when they sum to zero). */
static void fill_cdf(float *cdf, const double *w, uint32_t n)
{
    double total = 0.0, acc = 0.0;
    for (uint32_t i = 0; i < n; i++)
        total += w[i];
    cdf[0] = 0.0f;
    for (uint32_t i = 0; i < n; i++) {
        acc += w[i];
        cdf[i + 1] = total > 0.0 ? (float)(acc / total) : (float)(i + 1) / (float)n;
    }
    if (n)
        cdf[n] = 1.0f;
}

/* The emissive triangles (photon kernels: lights, light_cdf) and the path
 * kernel's table of those and the scene's point, spot and directional
 * lights and environment map (pt_lights, pt_light_cdf; a constant sky is
 * left to BSDF sampling, kernel_path.h), both in proportion to power as
 * scene/lights.c: an area light's Phi = pi A L (one face; twice for
 * two-sided), the others' il_light.power, by luminance. */
static il_status pack_lights(const il_scene *scene, il_kscene *out, il_error *err)
{
    uint32_t n = 0, nd = 0;
    for (uint32_t i = 0; i < out->bvh.num_tris; i++)
        n += !v3_is_zero(scene->materials[out->bvh.tris[i].pad].emission);
    for (uint32_t i = 0; i < scene->num_lights; i++) {
        il_light_kind k = scene->lights[i].kind;
        nd += k != IL_LIGHTK_AREA;
    }
    out->lights = il_malloc(sizeof *out->lights * (n ? n : 1), err);
    out->light_cdf = il_malloc(sizeof *out->light_cdf * (n + 1), err);
    out->pt_lights = il_calloc(n + nd ? n + nd : 1, sizeof *out->pt_lights, err);
    out->pt_light_cdf = il_malloc(sizeof *out->pt_light_cdf * (n + nd + 1), err);
    double *power = malloc(sizeof *power * (n + nd ? n + nd : 1));
    if (!out->lights || !out->light_cdf || !out->pt_lights || !out->pt_light_cdf || !power) {
        free(power);
        return il_fail(err, IL_ERR_MEMORY, "out of memory packing the lights");
    }
    uint32_t k = 0;
    for (uint32_t i = 0; i < out->bvh.num_tris; i++) {
        const ilk_tri *t = &out->bvh.tris[i];
        const il_material *m = &scene->materials[t->pad];
        if (v3_is_zero(m->emission))
            continue;
        ilk_vec3 c = ilk_cross(t->e1, t->e2);
        double area = 0.5 * sqrt((double)ilk_dot(c, c));
        power[k] = IL_PI * area * il_luminance(m->emission) * (m->two_sided ? 2.0 : 1.0);
        out->pt_lights[k].kind = ILK_LIGHT_AREA;
        out->pt_lights[k].tri = i;
        out->lights[k++] = i;
    }
    out->num_lights = n;
    fill_cdf(out->light_cdf, power, n);
    for (uint32_t i = 0; i < scene->num_lights; i++) {
        const il_light *l = &scene->lights[i];
        ilk_light *d = &out->pt_lights[k];
        switch (l->kind) {
        case IL_LIGHTK_POINT: d->kind = ILK_LIGHT_POINT; break;
        case IL_LIGHTK_SPOT: d->kind = ILK_LIGHT_SPOT; break;
        case IL_LIGHTK_DIRECTIONAL: d->kind = ILK_LIGHT_DIRECTIONAL; break;
        case IL_LIGHTK_ENVIRONMENT:
            if (!scene->envmap)
                continue;
            d->kind = ILK_LIGHT_ENVIRONMENT;
            break;
        default: continue;
        }
        d->position = to_k(l->position);
        d->direction = to_k(l->direction);
        d->intensity = to_k(l->intensity);
        d->cos_cutoff = l->cos_cutoff;
        d->spot_exponent = l->spot_exponent;
        power[k++] = l->power;
    }
    out->num_pt_lights = k;
    fill_cdf(out->pt_light_cdf, power, k);
    if (n) {
        out->tri_light_pmf = il_calloc(out->bvh.num_tris, sizeof *out->tri_light_pmf, err);
        if (!out->tri_light_pmf) {
            free(power);
            return IL_ERR_MEMORY;
        }
    }
    for (uint32_t i = 0; i < k; i++) {
        float pmf = out->pt_light_cdf[i + 1] - out->pt_light_cdf[i];
        if (out->pt_lights[i].kind == ILK_LIGHT_ENVIRONMENT)
            out->env_light_pmf = pmf;
        else if (out->pt_lights[i].kind == ILK_LIGHT_AREA)
            out->tri_light_pmf[out->pt_lights[i].tri] = pmf;
    }
    free(power);
    return IL_OK;
}

static il_status build(const il_scene *scene, uint32_t width, uint32_t height, uint32_t max_depth, uint64_t seed,
                       bool extended, il_kscene *out, il_error *err)
{
    memset(out, 0, sizeof *out);
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "kernel scene: the scene is not committed");
    il_status st = check_supported(scene, extended, err);
    if (st != IL_OK)
        return st;
    if ((st = il_kbvh_build_scene(scene, &out->bvh, err)) != IL_OK)
        return st;
    out->num_materials = scene->num_materials;
    out->materials = il_calloc(scene->num_materials ? scene->num_materials : 1, sizeof *out->materials, err);
    if (!out->materials) {
        il_kscene_free(out);
        return IL_ERR_MEMORY;
    }
    for (uint32_t i = 0; i < scene->num_materials; i++)
        pack_material(&scene->materials[i], &out->materials[i]);
    if ((st = pack_normals(scene, out, err)) != IL_OK || (st = pack_lights(scene, out, err)) != IL_OK ||
        (st = pack_textures(scene, out, err)) != IL_OK || (st = pack_envmap(scene, out, err)) != IL_OK) {
        il_kscene_free(out);
        return st;
    }

    il_camera_desc cd;
    il_scene_get_camera(scene, &cd);
    il_camera cam;
    il_camera_init(&cam, &cd, width, height);
    ilk_scene *v = &out->view;
    v->bvh = il_kbvh_view(&out->bvh);
    v->materials = out->materials;
    v->lights = out->lights;
    v->light_cdf = out->light_cdf;
    v->num_lights = out->num_lights;
    v->pt_lights = out->pt_lights;
    v->pt_light_cdf = out->pt_light_cdf;
    v->num_pt_lights = out->num_pt_lights;
    v->normals = out->normals;
    v->uvs = out->uvs;
    v->textures = out->textures;
    v->texels = out->texels;
    /* A uniform sky, or a map (pack_envmap). */
    v->has_environment = scene->has_environment ? 1u : 0u;
    v->environment = scene->has_environment ? to_k(scene->environment.radiance) : ilk_v3(0, 0, 0);
    v->env_texels = out->env_texels;
    v->env_width = out->env_width;
    v->env_height = out->env_height;
    v->env_cos_rot = scene->envmap ? scene->envmap->cos_rot : 1.0f;
    v->env_sin_rot = scene->envmap ? scene->envmap->sin_rot : 0.0f;
    v->env_cdf = out->env_cdf;
    v->env_grid_w = out->env_grid_w;
    v->env_grid_h = out->env_grid_h;
    v->env_light_pmf = out->env_light_pmf;
    v->tri_light_pmf = out->tri_light_pmf;
    for (uint32_t i = 0; i < scene->num_discs; i++)
        v->discs[i] = (ilk_disc){.towards = to_k(scene->discs[i].towards),
                                 .sin2_radius = scene->discs[i].sin2_radius,
                                 .radiance = to_k(scene->discs[i].radiance)};
    v->num_discs = scene->num_discs;
    v->epsilon = il_trace_epsilon(scene->tracer);
    v->camera.position = to_k(cam.position);
    v->camera.forward = to_k(cam.forward);
    v->camera.right = to_k(cam.right);
    v->camera.up = to_k(cam.up);
    v->camera.tan_half_x = cam.tan_half_x;
    v->camera.tan_half_y = cam.tan_half_y;
    v->camera.inv_width = cam.inv_width;
    v->camera.inv_height = cam.inv_height;
    v->width = width;
    v->height = height;
    v->max_depth = max_depth ? max_depth : 8;
    v->seed = seed;
    return IL_OK;
}

il_status il_kscene_build(const il_scene *scene, uint32_t width, uint32_t height, uint32_t max_depth,
                          uint64_t seed, il_kscene *out, il_error *err)
{
    return build(scene, width, height, max_depth, seed, false, out, err);
}

il_status il_kscene_build_pt(const il_scene *scene, uint32_t width, uint32_t height, uint32_t max_depth,
                             uint64_t seed, il_kscene *out, il_error *err)
{
    return build(scene, width, height, max_depth, seed, true, out, err);
}

void il_kscene_free(il_kscene *ks)
{
    il_kbvh_free(&ks->bvh);
    free(ks->materials);
    free(ks->lights);
    free(ks->light_cdf);
    free(ks->pt_lights);
    free(ks->pt_light_cdf);
    free(ks->normals);
    free(ks->uvs);
    free(ks->textures);
    free(ks->texels);
    free(ks->env_texels);
    free(ks->env_cdf);
    free(ks->tri_light_pmf);
    memset(ks, 0, sizeof *ks);
}
