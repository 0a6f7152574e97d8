/* Mesh files through assimp's C API: meshes (node transforms applied here),
 * materials mapped onto illum's model, textures, lights and the camera.
 * The mapping is documented in docs/scene-format.md, "Materials from OBJ/MTL
 * and glTF" and "Lights and cameras in mesh files". */
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/color.h"
#include "core/error.h"
#include "image/image_io.h"
#include "image/srgb.h"
#include "scene/loader.h"
#include "scene/mesh_open.h"
#include "scene/pane.h"
#include "scene/scene.h"
#include "scene/xform.h"

/* An exponent at or above this is a perfect mirror (MTL Ns, glTF roughness). */
#define IL_MIRROR_EXPONENT 1000.0f

/* assimp's matrices are row-major with the translation in a4, b4, c4. */
static il_xform from_ai(const struct aiMatrix4x4 *a)
{
    il_xform x = {{{a->a1, a->a2, a->a3, a->a4},
                   {a->b1, a->b2, a->b3, a->b4},
                   {a->c1, a->c2, a->c3, a->c4},
                   {a->d1, a->d2, a->d3, a->d4}}};
    return x;
}

/* ----------------------------------------------------------- load context */

#define IL_PATH_MAX 2048

typedef struct tex_cache_entry {
    char key[IL_PATH_MAX];
    uint32_t handle; /* 0: failed to load */
} tex_cache_entry;

typedef struct loader {
    il_scene *scene;
    const char *path;
    char dir[IL_PATH_MAX];         /* the file's folder, with a trailing '/' or empty */
    const struct aiScene *ai;
    const il_assimp_options *opt;
    bool gltf;
    uint32_t *material_map;        /* per aiMaterial: scene index, or UINT32_MAX if not yet made */
    uint32_t *pane_map;            /* per aiMaterial: its thin_glass twin for open meshes, or
                                      UINT32_MAX if not yet made */
    float *emissive_strength;      /* glTF: per material, from the JSON; NULL if none */
    tex_cache_entry *tex_cache;
    uint32_t num_tex_cache;
    uint64_t skipped_faces;        /* points and lines */
    il_error *err;
} loader;

static bool has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), m = strlen(ext);
    return n > m && strcasecmp(path + n - m, ext) == 0;
}

/* Drops the faces that have no vertex indices (a corrupt PLY can hold
 * them), which assimp 5.2's triangulation does not expect: it aborts the
 * program (an ai_assert in TriangulateProcess.cpp) instead of failing.
 * Each mesh's primitive types are recomputed from the faces kept.  Faces
 * are swapped, not copied, so that every index array stays owned by one
 * face for assimp to free.  A mesh whose faces are all empty is an error
 * (false, the scene untouched): a mesh left with no faces makes the
 * post-processing fail, and assimp 5.2 crashes releasing the scene then.
 * *dropped: how many were dropped. */
static bool drop_empty_faces(struct aiScene *ai, uint64_t *dropped)
{
    *dropped = 0;
    for (unsigned m = 0; m < ai->mNumMeshes; m++) {
        const struct aiMesh *mesh = ai->mMeshes[m];
        unsigned f = 0;
        while (f < mesh->mNumFaces && mesh->mFaces[f].mNumIndices == 0)
            f++;
        if (mesh->mNumFaces > 0 && f == mesh->mNumFaces)
            return false;
    }
    for (unsigned m = 0; m < ai->mNumMeshes; m++) {
        struct aiMesh *mesh = ai->mMeshes[m];
        unsigned kept = 0, types = 0;
        for (unsigned f = 0; f < mesh->mNumFaces; f++) {
            struct aiFace face = mesh->mFaces[f];
            unsigned n = face.mNumIndices;
            if (n == 0)
                continue;
            mesh->mFaces[f] = mesh->mFaces[kept];
            mesh->mFaces[kept++] = face;
            types |= n == 1 ? aiPrimitiveType_POINT
                   : n == 2 ? aiPrimitiveType_LINE
                   : n == 3 ? aiPrimitiveType_TRIANGLE
                            : aiPrimitiveType_POLYGON;
        }
        if (kept < mesh->mNumFaces) {
            *dropped += mesh->mNumFaces - kept;
            mesh->mNumFaces = kept;
            mesh->mPrimitiveTypes = types;
        }
    }
    return true;
}

/* ---------------------------------------------------------------- textures */

/* Decodes an embedded texture: compressed (PNG/JPEG bytes) or raw BGRA8 texels. */
static il_status decode_embedded(const struct aiTexture *t, const char *name, il_image *img,
                                 il_error *err)
{
    if (t->mHeight == 0) {
        const unsigned char *d = (const unsigned char *)t->pcData;
        size_t n = t->mWidth;
        if (n >= 8 && d[0] == 0x89 && d[1] == 'P' && d[2] == 'N' && d[3] == 'G')
            return il_png_read(d, n, name, img, err);
        if (n >= 3 && d[0] == 0xFF && d[1] == 0xD8)
            return il_jpeg_read(d, n, name, img, err);
        return il_fail(err, IL_ERR_FORMAT, "%s: embedded texture of an unsupported format '%s'",
                       name, t->achFormatHint);
    }
    il_status s = il_image_alloc(img, t->mWidth, t->mHeight, err);
    if (s != IL_OK)
        return s;
    size_t n = (size_t)t->mWidth * t->mHeight;
    for (size_t i = 0; i < n; i++) {
        const struct aiTexel *px = &t->pcData[i];
        img->rgb[3 * i + 0] = (float)il_srgb_to_linear(px->r / 255.0);
        img->rgb[3 * i + 1] = (float)il_srgb_to_linear(px->g / 255.0);
        img->rgb[3 * i + 2] = (float)il_srgb_to_linear(px->b / 255.0);
    }
    return IL_OK;
}

/* Loads (once per file) the texture a material names; 0 with a warning when it
 * cannot be read: the material keeps its plain colour. */
static uint32_t load_texture(loader *L, const char *tex_path, const char *material_name)
{
    for (uint32_t i = 0; i < L->num_tex_cache; i++)
        if (strcmp(L->tex_cache[i].key, tex_path) == 0)
            return L->tex_cache[i].handle;

    il_image img = {0};
    il_error e = {0};
    il_status s;
    char shown[2 * IL_PATH_MAX];
    int len;
    const struct aiTexture *emb = NULL;
    if (tex_path[0] == '*') {
        unsigned idx = (unsigned)strtoul(tex_path + 1, NULL, 10);
        if (idx < L->ai->mNumTextures)
            emb = L->ai->mTextures[idx];
    } else {
        for (unsigned i = 0; i < L->ai->mNumTextures; i++)
            if (strcmp(L->ai->mTextures[i]->mFilename.data, tex_path) == 0)
                emb = L->ai->mTextures[i];
    }
    if (emb || tex_path[0] == '*') {
        len = snprintf(shown, sizeof shown, "%s (embedded texture %s)", L->path, tex_path);
        s = emb ? decode_embedded(emb, shown, &img, &e)
                : il_fail(&e, IL_ERR_FORMAT, "no such embedded texture");
    } else {
        /* Relative to the model's folder; MTL files written on Windows use '\'. */
        char rel[IL_PATH_MAX];
        len = snprintf(rel, sizeof rel, "%s", tex_path);
        for (char *c = rel; *c; c++)
            if (*c == '\\')
                *c = '/';
        len = rel[0] == '/' ? snprintf(shown, sizeof shown, "%s", rel)
                            : snprintf(shown, sizeof shown, "%s%s", L->dir, rel);
        s = il_image_read(shown, &img, &e);
    }
    if (len < 0 || (size_t)len >= sizeof shown)
        s = il_fail(&e, IL_ERR_IO, "path too long");
    uint32_t handle = 0;
    if (s == IL_OK)
        s = il_scene_add_texture(L->scene, img.width, img.height, img.rgb, &handle, &e);
    il_image_free(&img);
    if (s != IL_OK) {
        handle = 0;
        il_scene_warn(L->scene, "%s: material '%s': texture %s not loaded (%s); using the "
                      "material colour", L->path, material_name, shown, e.message);
    }
    tex_cache_entry *grown = realloc(L->tex_cache, (L->num_tex_cache + 1) * sizeof *grown);
    if (grown) {
        L->tex_cache = grown;
        if (snprintf(grown[L->num_tex_cache].key, sizeof grown->key, "%s", tex_path) <
            (int)sizeof grown->key) {
            grown[L->num_tex_cache].handle = handle;
            L->num_tex_cache++;
        }
    }
    return handle;
}

/* --------------------------------------------------------------- materials */

static bool get_color(const struct aiMaterial *m, const char *key, il_vec3 *out)
{
    struct aiColor4D c;
    if (aiGetMaterialColor(m, key, 0, 0, &c) != AI_SUCCESS)
        return false;
    *out = v3(c.r, c.g, c.b);
    return v3_is_finite(*out);
}

static bool get_float(const struct aiMaterial *m, const char *key, float *out)
{
    unsigned n = 1;
    float f;
    if (aiGetMaterialFloatArray(m, key, 0, 0, &f, &n) != AI_SUCCESS || n < 1 || !isfinite(f))
        return false;
    *out = f;
    return true;
}

static bool get_int(const struct aiMaterial *m, const char *key, int *out)
{
    const struct aiMaterialProperty *p;
    if (aiGetMaterialProperty(m, key, 0, 0, &p) != AI_SUCCESS || p->mType != aiPTI_Integer ||
        p->mDataLength < sizeof(int32_t))
        return false;
    int32_t i;
    memcpy(&i, p->mData, sizeof i);
    *out = i;
    return true;
}

/* A flag stored as an int or as a one-byte bool (glTF's $mat.twosided). */
static bool get_flag(const struct aiMaterial *m, const char *key)
{
    int i;
    if (get_int(m, key, &i))
        return i != 0;
    const struct aiMaterialProperty *p;
    if (aiGetMaterialProperty(m, key, 0, 0, &p) != AI_SUCCESS || p->mDataLength < 1)
        return false;
    return p->mData[0] != 0;
}

static il_vec3 clamp_colour(il_vec3 c)
{
    return v3(fmaxf(c.x, 0.0f), fmaxf(c.y, 0.0f), fmaxf(c.z, 0.0f));
}

/* glTF 2.0 metallic-roughness onto illum's model (docs/scene-format.md). */
static void map_gltf(loader *L, const struct aiMaterial *m, uint32_t index, il_material_desc *d)
{
    il_vec3 base = v3s(1.0f), emissive = v3s(0.0f);
    float metallic = 1.0f, roughness = 1.0f, transmission = 0.0f, ior = 1.5f, strength = 1.0f;
    if (!get_color(m, "$clr.base", &base))
        get_color(m, "$clr.diffuse", &base);
    get_float(m, "$mat.metallicFactor", &metallic);
    get_float(m, "$mat.roughnessFactor", &roughness);
    get_float(m, "$mat.transmission.factor", &transmission);
    get_float(m, "$mat.refracti", &ior);
    get_color(m, "$clr.emissive", &emissive);
    /* KHR_materials_emissive_strength: newer assimp reports it as
     * AI_MATKEY_EMISSIVE_INTENSITY; assimp 5.2.5 drops it, so it is also read
     * from the file's JSON (gltf_emissive_strengths). */
    if (!get_float(m, "$mat.emissiveIntensity", &strength) && L->emissive_strength)
        strength = L->emissive_strength[index];
    base = clamp_colour(base);
    metallic = il_clampf(metallic, 0.0f, 1.0f);
    roughness = il_clampf(roughness, 0.0f, 1.0f);

    d->emission = v3_scale(clamp_colour(emissive), fmaxf(strength, 0.0f));
    d->two_sided = get_flag(m, "$mat.twosided");

    /* Phong exponent equivalent to a GGX/Beckmann roughness: alpha = roughness^2
     * (Burley 2012, section 5.4), n = 2/alpha^2 - 2 (Walter et al. 2007, eq. 33
     * for the Beckmann-Phong correspondence). */
    float alpha = roughness * roughness;
    float n = alpha > 1e-4f ? 2.0f / (alpha * alpha) - 2.0f : 1e8f;
    n = il_clampf(n, 1.0f, 1e6f);

    if (transmission >= 0.5f && metallic < 0.5f) {
        d->type = IL_MATERIAL_DIELECTRIC;
        d->specular = base;
        d->ior = ior > 1.0f ? ior : 1.5f;
        d->diffuse = base;
    } else if (metallic >= 0.5f) {
        if (n >= IL_MIRROR_EXPONENT) {
            d->type = IL_MATERIAL_MIRROR;
            d->specular = base;
        } else {
            d->type = IL_MATERIAL_PHONG;
            d->diffuse = v3_scale(base, 1.0f - metallic);
            d->specular = base;
            d->exponent = n;
        }
    } else {
        d->type = IL_MATERIAL_DIFFUSE;
        d->diffuse = base;
    }
}

/* Wavefront MTL (and other classic Phong-style materials) onto illum's model. */
static void map_mtl(const struct aiMaterial *m, il_material_desc *d)
{
    il_vec3 kd = v3s(0.8f), ks = v3s(0.0f), ke = v3s(0.0f);
    float ns = 0.0f, ni = 1.0f, opacity = 1.0f;
    int illum = 2;
    get_color(m, "$clr.diffuse", &kd);
    get_color(m, "$clr.specular", &ks);
    get_color(m, "$clr.emissive", &ke);
    get_float(m, "$mat.shininess", &ns);
    get_float(m, "$mat.refracti", &ni);
    get_float(m, "$mat.opacity", &opacity);
    if (!get_int(m, "$mat.illum", &illum)) {
        /* Formats without an MTL illum: a specular colour means highlights. */
        illum = 2;
    }
    kd = clamp_colour(kd);
    ks = clamp_colour(ks);
    d->emission = clamp_colour(ke);

    bool has_specular = v3_max_comp(ks) > 0.0f && illum >= 2;
    /* illum 4, 6, 7, 9 are the MTL spec's transparent models ("glass", "refraction"). */
    bool glass = illum == 4 || illum == 6 || illum == 7 || illum == 9 || opacity < 1.0f;
    if (glass) {
        d->type = IL_MATERIAL_DIELECTRIC;
        d->specular = v3s(1.0f);
        d->ior = ni > 1.0f ? ni : 1.5f; /* assimp reports Ni = 1 when absent */
        d->diffuse = kd;
    } else if (has_specular && (illum == 5 || ns >= IL_MIRROR_EXPONENT)) {
        d->type = IL_MATERIAL_MIRROR;
        d->specular = ks;
        d->diffuse = kd;
    } else if (has_specular) {
        d->type = IL_MATERIAL_PHONG;
        d->diffuse = kd;
        d->specular = ks;
        d->exponent = ns >= 1.0f ? ns : 1.0f;
    } else {
        d->type = IL_MATERIAL_DIFFUSE;
        d->diffuse = kd;
    }
}

/* A mesh's triangles, for the choice between glass and a pane. */
typedef struct mesh_shape {
    const char *name;
    const float *positions;
    uint32_t num_vertices;
    const uint32_t *indices;
    uint32_t num_triangles;
} mesh_shape;

/* True for an MTL material that asks for refraction (illum 6 or 7): a
 * water surface is one sheet whose medium the container's walls close. */
static bool refracting(const loader *L, unsigned i)
{
    int illum = 2;
    return !L->gltf && get_int(L->ai->mMaterials[i], "$mat.illum", &illum) && (illum == 6 || illum == 7);
}

/* A transparent material (DIELECTRIC) that does not ask for refraction, on
 * an open mesh such as a window modelled as one sheet, would bend light in
 * and never out: the mesh gets the material as a thin pane instead (the
 * same name and ior; a pane is neutral, so a tint becomes its
 * transmittance, clear glass's times the tint's luminance).  *pane says
 * whether it does. */
static il_status as_pane(loader *L, unsigned i, const mesh_shape *shape, il_material_desc *d,
                         bool *pane)
{
    *pane = false;
    if (d->type != IL_MATERIAL_DIELECTRIC || refracting(L, i))
        return IL_OK;
    il_status s = il_mesh_is_open(shape->positions, shape->num_vertices, shape->indices,
                                  shape->num_triangles, pane, L->err);
    if (s != IL_OK || !*pane)
        return s;
    float ior = d->ior > 0.0f ? d->ior : 1.5f, tint = il_luminance(v3_max(d->specular, v3s(0.0f)));
    d->type = IL_MATERIAL_THIN_GLASS;
    d->transmittance = tint < 1.0f ? il_maxf(tint, 1e-3f) * il_pane_clear_transmittance(ior) : 0.0f;
    d->specular = v3s(0.0f);
    return IL_OK;
}

/* The scene material for aiMaterial i on a mesh of this shape, converted
 * on first use (once as glass and once as a pane, when both are needed). */
static il_status material_for(loader *L, unsigned i, const mesh_shape *shape, uint32_t *out)
{
    if (L->opt->material_override) {
        *out = L->opt->material_override;
        return IL_OK;
    }
    if (i >= L->ai->mNumMaterials) {
        *out = 0;
        return IL_OK;
    }
    if (L->material_map[i] != UINT32_MAX && L->material_map[i] == L->pane_map[i]) {
        *out = L->material_map[i];   /* the scene file's own material, or not glass */
        return IL_OK;
    }
    const struct aiMaterial *m = L->ai->mMaterials[i];
    struct aiString name = {0};
    aiGetMaterialString(m, "?mat.name", 0, 0, &name);
    if (L->opt->lookup) {
        uint32_t r = L->opt->lookup(name.data, L->opt->lookup_user);
        if (r) {
            /* The scene file's own material, on open meshes too. */
            *out = L->material_map[i] = L->pane_map[i] = r;
            return IL_OK;
        }
    }
    il_material_desc d = {0};
    d.name = name.data[0] ? name.data : "unnamed";
    if (L->gltf)
        map_gltf(L, m, i, &d);
    else
        map_mtl(m, &d);

    if (d.type == IL_MATERIAL_DIFFUSE || d.type == IL_MATERIAL_PHONG) {
        struct aiString tex = {0};
        if (aiGetMaterialTexture(m, aiTextureType_DIFFUSE, 0, &tex, NULL, NULL, NULL, NULL, NULL,
                                 NULL) == AI_SUCCESS ||
            aiGetMaterialTexture(m, aiTextureType_BASE_COLOR, 0, &tex, NULL, NULL, NULL, NULL,
                                 NULL, NULL) == AI_SUCCESS) {
            if (tex.data[0])
                d.diffuse_texture = load_texture(L, tex.data, d.name);
        }
    }
    bool pane;
    il_status s = as_pane(L, i, shape, &d, &pane);
    if (s != IL_OK)
        return s;
    uint32_t *slot = pane ? &L->pane_map[i] : &L->material_map[i];
    if (*slot != UINT32_MAX) {
        *out = *slot;
        return IL_OK;
    }
    if (pane)
        il_scene_warn(L->scene, "%s: material '%s' is transparent on an open mesh ('%s', a single "
                      "sheet): taken as a thin pane (thin_glass), which passes light straight "
                      "through; refraction needs a closed solid (docs/materials.md)",
                      L->path, d.name, shape->name);
    uint32_t idx;
    s = il_scene_add_material(L->scene, &d, &idx, L->err);
    if (s != IL_OK)
        return il_load_prefix_error(L->err, s, L->path, NULL);
    *out = *slot = idx;
    if (d.type != IL_MATERIAL_DIELECTRIC && !pane)
        L->pane_map[i] = idx;        /* not glass: the same on any mesh */
    return IL_OK;
}

/* ------------------------------------------------------------------ meshes */

static il_status add_mesh(loader *L, const struct aiMesh *am, const struct aiNode *node,
                          const il_xform *x)
{
    uint32_t nv = am->mNumVertices;
    uint32_t ntri = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        if (am->mFaces[f].mNumIndices == 3)
            ntri++;
        else
            L->skipped_faces++;
    }
    if (ntri == 0 || nv == 0)
        return IL_OK;

    il_status s = IL_ERR_MEMORY;
    float *pos = il_malloc((size_t)nv * 3 * sizeof(float), L->err);
    float *nrm = am->mNormals ? il_malloc((size_t)nv * 3 * sizeof(float), L->err) : NULL;
    float *uv = am->mTextureCoords[0] ? il_malloc((size_t)nv * 2 * sizeof(float), L->err) : NULL;
    uint32_t *idx = il_malloc((size_t)ntri * 3 * sizeof(uint32_t), L->err);
    if (!pos || !idx || (am->mNormals && !nrm) || (am->mTextureCoords[0] && !uv))
        goto done;
    for (uint32_t v = 0; v < nv; v++) {
        pos[3 * v] = am->mVertices[v].x;
        pos[3 * v + 1] = am->mVertices[v].y;
        pos[3 * v + 2] = am->mVertices[v].z;
        if (nrm) {
            nrm[3 * v] = am->mNormals[v].x;
            nrm[3 * v + 1] = am->mNormals[v].y;
            nrm[3 * v + 2] = am->mNormals[v].z;
        }
        if (uv) {
            uv[2 * v] = am->mTextureCoords[0][v].x;
            uv[2 * v + 1] = am->mTextureCoords[0][v].y;
        }
    }
    uint32_t t = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *face = &am->mFaces[f];
        if (face->mNumIndices != 3)
            continue;
        memcpy(idx + 3 * t, face->mIndices, 3 * sizeof(uint32_t));
        t++;
    }

    uint32_t mat;
    const char *name = am->mName.length ? am->mName.data : node->mName.data;
    const mesh_shape shape = {name, pos, nv, idx, ntri};
    s = material_for(L, am->mMaterialIndex, &shape, &mat);
    if (s != IL_OK)
        goto done;
    il_mesh_desc d = {
        .name = name,
        .num_vertices = nv,
        .num_triangles = ntri,
        .positions = pos,
        .normals = nrm,
        .uvs = uv,
        .indices = idx,
        .material = mat,
    };
    s = il_load_add_mesh(L->scene, &d, x, L->err);
    if (s != IL_OK)
        il_load_prefix_error(L->err, s, L->path, NULL);
done:
    free(pos);
    free(nrm);
    free(uv);
    free(idx);
    return s;
}

static il_status walk_nodes(loader *L, const struct aiNode *node, const il_xform *parent, int depth)
{
    if (depth > 1000)
        return il_fail(L->err, IL_ERR_FORMAT, "%s: node hierarchy too deep", L->path);
    il_xform local = from_ai(&node->mTransformation);
    il_xform x = il_xform_mul(parent, &local);
    for (unsigned i = 0; i < node->mNumMeshes; i++) {
        unsigned mi = node->mMeshes[i];
        if (mi >= L->ai->mNumMeshes)
            continue;
        il_status s = add_mesh(L, L->ai->mMeshes[mi], node, &x);
        if (s != IL_OK)
            return s;
    }
    for (unsigned i = 0; i < node->mNumChildren; i++) {
        il_status s = walk_nodes(L, node->mChildren[i], &x, depth + 1);
        if (s != IL_OK)
            return s;
    }
    return IL_OK;
}

/* The world transform of the node called `name` (lights and cameras are tied
 * to their node by name).  False when there is none. */
static bool find_node(const struct aiNode *node, const char *name, const il_xform *parent,
                      il_xform *out, int depth)
{
    if (depth > 1000)
        return false;
    il_xform local = from_ai(&node->mTransformation);
    il_xform x = il_xform_mul(parent, &local);
    if (strcmp(node->mName.data, name) == 0) {
        *out = x;
        return true;
    }
    for (unsigned i = 0; i < node->mNumChildren; i++)
        if (find_node(node->mChildren[i], name, &x, out, depth + 1))
            return true;
    return false;
}

/* ------------------------------------------------------- lights and camera */

static il_status add_lights(loader *L, const il_xform *root)
{
    for (unsigned i = 0; i < L->ai->mNumLights; i++) {
        const struct aiLight *al = L->ai->mLights[i];
        il_xform x;
        if (!find_node(L->ai->mRootNode, al->mName.data, root, &x, 0))
            x = *root;
        il_light_desc d = {0};
        switch (al->mType) {
        case aiLightSource_POINT: d.type = IL_LIGHT_POINT; break;
        case aiLightSource_SPOT: d.type = IL_LIGHT_SPOT; break;
        case aiLightSource_DIRECTIONAL: d.type = IL_LIGHT_DIRECTIONAL; break;
        default:
            il_scene_warn(L->scene, "%s: light '%s' of an unsupported kind (ambient or area) "
                          "ignored", L->path, al->mName.data);
            continue;
        }
        d.position = il_xform_point(&x, al->mPosition.x, al->mPosition.y, al->mPosition.z);
        d.direction = v3_normalize(il_xform_vector(&x, al->mDirection.x, al->mDirection.y,
                                             al->mDirection.z));
        /* assimp's glTF importer gives colour x intensity: candela for point and
         * spot lights, lux for directional ones (KHR_lights_punctual). */
        il_vec3 c = clamp_colour(v3(al->mColorDiffuse.r, al->mColorDiffuse.g, al->mColorDiffuse.b));
        d.intensity = L->gltf ? v3_scale(c, 1.0f / IL_LUMENS_PER_WATT) : c;
        if (d.type == IL_LIGHT_SPOT) {
            /* The outer cone is the cut-off; illum's spot has no smooth edge
             * between the inner and outer cones. */
            float outer = al->mAngleOuterCone * 180.0f / IL_PI;
            d.spot_angle = (outer > 0.0f && outer <= 180.0f) ? outer : 45.0f;
        }
        if (d.type != IL_LIGHT_POINT && v3_is_zero(d.direction))
            d.direction = v3(0, -1, 0);
        il_error e = {0};
        if (il_scene_add_light(L->scene, &d, &e) != IL_OK)
            il_scene_warn(L->scene, "%s: light '%s' ignored: %s", L->path, al->mName.data,
                          e.message);
    }
    return IL_OK;
}

static void set_camera(loader *L, const il_xform *root)
{
    if (L->ai->mNumCameras == 0)
        return;
    if (L->scene->camera.present) {
        il_scene_warn(L->scene, "%s: the file's camera is ignored: the scene already has one",
                      L->path);
        return;
    }
    const struct aiCamera *ac = L->ai->mCameras[0];
    il_xform x;
    if (!find_node(L->ai->mRootNode, ac->mName.data, root, &x, 0))
        x = *root;
    /* assimp 5.2.5's glTF importer also copies the node's translation into
     * mPosition although the node transform carries it: the camera sits at the
     * node's origin. */
    struct aiVector3D p = L->gltf ? (struct aiVector3D){0, 0, 0} : ac->mPosition;
    il_vec3 pos = il_xform_point(&x, p.x, p.y, p.z);
    il_vec3 dir = v3_normalize(il_xform_vector(&x, ac->mLookAt.x, ac->mLookAt.y, ac->mLookAt.z));
    il_vec3 up = v3_normalize(il_xform_vector(&x, ac->mUp.x, ac->mUp.y, ac->mUp.z));
    float aspect = ac->mAspect > 0.0f ? ac->mAspect : 1.0f;
    float fov_y;
    if (L->gltf) {
        /* assimp 5.2.5 stores yfov * aspectRatio in mHorizontalFOV. */
        fov_y = ac->mHorizontalFOV / aspect;
    } else {
        /* Importers store the full horizontal angle (despite aiCamera's
         * comment); vertical from horizontal: tan(fy/2) = tan(fx/2) / aspect. */
        fov_y = 2.0f * atanf(tanf(0.5f * ac->mHorizontalFOV) / aspect);
    }
    il_camera_desc c = {
        .position = pos,
        .target = v3_add(pos, dir),
        .up = up,
        .fov_y = fov_y * 180.0f / IL_PI,
    };
    if (!(c.fov_y > 0.0f && c.fov_y < 180.0f))
        c.fov_y = 0.0f;
    il_error e = {0};
    if (il_scene_set_camera(L->scene, &c, &e) != IL_OK)
        il_scene_warn(L->scene, "%s: camera '%s' ignored: %s", L->path, ac->mName.data, e.message);
}

/* ---------------------------------------- glTF: KHR_materials_emissive_strength */

/* The JSON of a .gltf file, or the JSON chunk of a .glb (glTF 2.0 spec,
 * section 4.4 "Binary glTF layout"). */
static cJSON *gltf_json(const char *path)
{
    char *buf;
    size_t n;
    if (il_load_read_file(path, &buf, &n, NULL) != IL_OK)
        return NULL;
    cJSON *j = NULL;
    const unsigned char *u = (const unsigned char *)buf;
    if (n >= 20 && memcmp(buf, "glTF", 4) == 0) {
        uint32_t len = u[12] | u[13] << 8 | u[14] << 16 | (uint32_t)u[15] << 24;
        if (memcmp(buf + 16, "JSON", 4) == 0 && len <= n - 20)
            j = cJSON_ParseWithLength(buf + 20, len);
    } else {
        j = cJSON_ParseWithLength(buf, n);
    }
    free(buf);
    return j;
}

/* Per assimp material, the emissive strength of the glTF material of the
 * same index and name (1 when absent); NULL when the file sets none. */
static float *gltf_emissive_strengths(const loader *L)
{
    cJSON *j = gltf_json(L->path);
    const cJSON *mats = cJSON_GetObjectItemCaseSensitive(j, "materials");
    float *out = NULL;
    for (unsigned i = 0; i < L->ai->mNumMaterials && cJSON_IsArray(mats); i++) {
        const cJSON *m = cJSON_GetArrayItem(mats, (int)i);
        const cJSON *ext = cJSON_GetObjectItemCaseSensitive(m, "extensions");
        const cJSON *es = cJSON_GetObjectItemCaseSensitive(ext, "KHR_materials_emissive_strength");
        const cJSON *v = cJSON_GetObjectItemCaseSensitive(es, "emissiveStrength");
        if (!cJSON_IsNumber(v))
            continue;
        /* Only when assimp kept the material order (same name). */
        struct aiString name = {0};
        aiGetMaterialString(L->ai->mMaterials[i], "?mat.name", 0, 0, &name);
        const cJSON *jn = cJSON_GetObjectItemCaseSensitive(m, "name");
        const char *want = cJSON_IsString(jn) ? jn->valuestring : "";
        if (want[0] && strcmp(want, name.data) != 0)
            continue;
        if (!out) {
            out = malloc(L->ai->mNumMaterials * sizeof *out);
            if (!out)
                break;
            for (unsigned k = 0; k < L->ai->mNumMaterials; k++)
                out[k] = 1.0f;
        }
        out[i] = isfinite(v->valuedouble) && v->valuedouble > 0 ? (float)v->valuedouble : 0.0f;
    }
    cJSON_Delete(j);
    return out;
}

/* ------------------------------------------------ OBJ: truncation checks */

/* assimp reads a cut-off OBJ without complaint (a last "v 0.5 0." becomes a
 * vertex, a last "f 1 2" a line).  The OBJ specification requires at least
 * three coordinates per "v" and three vertices per "f": anything less, or a
 * NUL byte, is reported as a corrupt or truncated file. */
static il_status obj_check(const char *path, il_error *err)
{
    char *text;
    size_t n;
    il_status s = il_load_read_file(path, &text, &n, err);
    if (s != IL_OK)
        return s;
    if (memchr(text, '\0', n)) {
        free(text);
        return il_fail(err, IL_ERR_FORMAT, "%s: binary data in an OBJ (text) file", path);
    }
    unsigned long line = 0;
    for (char *p = text; *p;) {
        line++;
        char *end = strchr(p, '\n');
        if (end)
            *end = '\0';
        while (*p == ' ' || *p == '\t')
            p++;
        bool vertex = p[0] == 'v' && (p[1] == ' ' || p[1] == '\t');
        bool face = p[0] == 'f' && (p[1] == ' ' || p[1] == '\t');
        if (vertex || face) {
            /* Count the whitespace-separated fields after the keyword. */
            int fields = 0;
            for (char *q = p + 1; *q;) {
                while (*q == ' ' || *q == '\t' || *q == '\r')
                    q++;
                if (!*q || *q == '#')
                    break;
                fields++;
                while (*q && *q != ' ' && *q != '\t' && *q != '\r')
                    q++;
            }
            if (fields < 3) {
                free(text);
                return il_fail(err, IL_ERR_FORMAT, "%s: line %lu: a %s with %d %s (at least 3 "
                               "needed): the file is corrupt or truncated", path, line,
                               vertex ? "vertex" : "face", fields,
                               vertex ? "coordinates" : "corners");
            }
        }
        if (!end)
            break;
        p = end + 1;
    }
    free(text);
    return IL_OK;
}

/* ------------------------------------------------------------------- entry */

il_status il_load_assimp(il_scene *scene, const char *path, const float *transform,
                         uint32_t material_override, il_error *err)
{
    il_assimp_options o = {.transform = transform, .material_override = material_override};
    return il_load_assimp_ex(scene, path, &o, err);
}

il_status il_load_assimp_ex(il_scene *scene, const char *path, const il_assimp_options *opt,
                            il_error *err)
{
    il_assimp_options none = {0};
    if (!opt)
        opt = &none;
    il_error local;
    if (!err)
        err = &local;
    FILE *f = fopen(path, "rb");
    if (!f)
        return il_fail(err, IL_ERR_IO, "%s: no such file", path);
    fclose(f);

    il_status cs = has_ext(path, ".obj")                              ? obj_check(path, err)
                   : has_ext(path, ".ply")                            ? il_ply_check(path, err)
                   : has_ext(path, ".gltf") || has_ext(path, ".glb") ? il_gltf_check(path, err)
                   : has_ext(path, ".off")                            ? il_off_check(path, err)
                                                                      : IL_OK;
    if (cs != IL_OK)
        return cs;

    /* Read and validated first, then faces without indices dropped, then
     * triangulated.  No normal generation: a mesh without normals is shaded
     * flat with its geometric normal, so flat faces stay flat.  Degenerate
     * faces are not removed here: il_scene_add_mesh drops and counts them. */
    const struct aiScene *ai = aiImportFile(path, aiProcess_ValidateDataStructure);
    if (!ai) {
        const char *msg = aiGetErrorString();
        return il_fail(err, IL_ERR_FORMAT, "%s: %s", path,
                       msg && msg[0] ? msg : "not a mesh file assimp can read");
    }
    uint64_t empty_faces = 0;
    if (!drop_empty_faces((struct aiScene *)ai, &empty_faces)) {
        aiReleaseImport(ai);
        return il_fail(err, IL_ERR_FORMAT, "%s: a mesh has faces but none with vertex indices", path);
    }
    ai = aiApplyPostProcessing(ai, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                       aiProcess_SortByPType);
    if (!ai) { /* assimp has released the scene */
        const char *msg = aiGetErrorString();
        return il_fail(err, IL_ERR_FORMAT, "%s: %s", path,
                       msg && msg[0] ? msg : "its faces could not be triangulated");
    }
    if (!ai->mRootNode || (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
        aiReleaseImport(ai);
        return il_fail(err, IL_ERR_FORMAT, "%s: incomplete scene (no geometry could be read)",
                       path);
    }

    loader L = {.scene = scene, .path = path, .ai = ai, .opt = opt, .err = err};
    L.gltf = has_ext(path, ".gltf") || has_ext(path, ".glb");
    const char *slash = strrchr(path, '/');
    if (slash && (size_t)(slash - path + 1) < sizeof L.dir)
        memcpy(L.dir, path, (size_t)(slash - path + 1));
    il_status s = IL_OK;
    L.material_map = il_malloc((ai->mNumMaterials + 1) * sizeof(uint32_t), err);
    L.pane_map = il_malloc((ai->mNumMaterials + 1) * sizeof(uint32_t), err);
    if (!L.material_map || !L.pane_map) {
        s = IL_ERR_MEMORY;
        goto done;
    }
    for (unsigned i = 0; i < ai->mNumMaterials; i++)
        L.material_map[i] = L.pane_map[i] = UINT32_MAX;
    if (L.gltf)
        L.emissive_strength = gltf_emissive_strengths(&L);

    il_xform root = opt->transform ? il_xform_from_cm(opt->transform) : il_xform_identity();

    uint32_t meshes_before = scene->num_meshes;
    uint64_t dropped_before = scene->dropped_triangles;
    s = walk_nodes(&L, ai->mRootNode, &root, 0);
    if (s != IL_OK)
        goto done;
    if (empty_faces)
        il_scene_warn(scene, "%s: faces without vertex indices ignored (%llu)", path,
                      (unsigned long long)empty_faces);
    if (L.skipped_faces)
        il_scene_warn(scene, "%s: %llu points/lines ignored (only triangles are rendered)", path,
                      (unsigned long long)L.skipped_faces);
    if (scene->num_meshes == meshes_before) {
        uint64_t dropped = scene->dropped_triangles - dropped_before;
        s = dropped ? il_fail(err, IL_ERR_INVALID, "%s: no triangles (all %llu dropped: NaN/Inf or "
                              "out-of-range coordinates, or zero area)", path,
                              (unsigned long long)dropped)
                    : il_fail(err, IL_ERR_INVALID, "%s: no triangles", path);
        goto done;
    }
    s = add_lights(&L, &root);
    if (s != IL_OK)
        goto done;
    set_camera(&L, &root);
done:
    free(L.material_map);
    free(L.pane_map);
    free(L.emissive_strength);
    free(L.tex_cache);
    aiReleaseImport(ai);
    return s;
}
