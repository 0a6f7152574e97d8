/* Baked meshes to glTF 2.0 (.glb, .gltf) through assimp's C export API
 * (<assimp/cexport.h>, aiExportScene with format "glb2" / "gltf2").
 *
 * The aiScene is built here in plain C from calloc'd structs and freed here:
 * aiExportScene takes it const and works on its own deep copy
 * (Assimp::Exporter::Export copies the scene first), so assimp never frees
 * what we allocated.  Layout: a root node with one child node per baked mesh
 * (named after it), one aiMesh per baked mesh with
 *   mVertices, mNormals,
 *   mColors[0] = display colour: linear radiance * 2^exposure clamped to [0,1],
 *                alpha 1 (glTF COLOR_0 is linear, glTF 2.0 spec 3.7.2.1),
 *   mColors[1] = the raw float radiance, alpha 1 (COLOR_1: nothing lost),
 * and one shared material: white, marked unlit (aiShadingMode_Unlit), since
 * the light is already in the colours.  assimp 5.2.5 writes it as a plain
 * white PBR material with metallic 0 (it does not emit KHR_materials_unlit).
 *
 * A .gltf gets its buffer in NAME.bin beside it: assimp names the buffer
 * after the part of the file name before ".gltf", which the temporary name
 * (NAME.gltf.tmp- and six random characters) keeps, so the renamed .gltf
 * finds it. */
#include <assimp/cexport.h>
#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/mesh.h>
#include <assimp/scene.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "scene/export.h"

static void set_string(struct aiString *s, const char *text)
{
    size_t n = strlen(text);
    if (n >= MAXLEN)
        n = MAXLEN - 1;
    memcpy(s->data, text, n);
    s->data[n] = '\0';
    s->length = (ai_uint32)n;
}

static void free_mesh(struct aiMesh *m)
{
    if (!m)
        return;
    free(m->mVertices);
    free(m->mNormals);
    free(m->mColors[0]);
    free(m->mColors[1]);
    if (m->mFaces)
        free(m->mFaces[0].mIndices); /* one block for all faces */
    free(m->mFaces);
    free(m);
}

static void free_material(struct aiMaterial *mat)
{
    if (!mat)
        return;
    for (unsigned i = 0; i < mat->mNumProperties; i++) {
        if (mat->mProperties[i])
            free(mat->mProperties[i]->mData);
        free(mat->mProperties[i]);
    }
    free(mat->mProperties);
    free(mat);
}

static void free_scene(struct aiScene *sc)
{
    if (!sc)
        return;
    if (sc->mRootNode) {
        for (unsigned i = 0; i < sc->mRootNode->mNumChildren; i++) {
            if (sc->mRootNode->mChildren[i])
                free(sc->mRootNode->mChildren[i]->mMeshes);
            free(sc->mRootNode->mChildren[i]);
        }
        free(sc->mRootNode->mChildren);
        free(sc->mRootNode);
    }
    for (unsigned i = 0; i < sc->mNumMeshes; i++)
        free_mesh(sc->mMeshes[i]);
    free(sc->mMeshes);
    for (unsigned i = 0; i < sc->mNumMaterials; i++)
        free_material(sc->mMaterials[i]);
    free(sc->mMaterials);
    free(sc);
}

/* Appends a material property; strings are stored as assimp stores aiString
 * values (a 32-bit length, the bytes, a terminating zero). */
static bool add_property(struct aiMaterial *mat, const char *key, enum aiPropertyTypeInfo type,
                         const void *data, unsigned size)
{
    struct aiMaterialProperty *p = calloc(1, sizeof *p);
    if (!p)
        return false;
    p->mData = malloc(size);
    if (!p->mData) {
        free(p);
        return false;
    }
    set_string(&p->mKey, key);
    p->mType = type;
    p->mDataLength = size;
    memcpy(p->mData, data, size);
    mat->mProperties[mat->mNumProperties++] = p;
    return true;
}

static struct aiMaterial *make_material(void)
{
    struct aiMaterial *mat = calloc(1, sizeof *mat);
    if (!mat)
        return NULL;
    mat->mNumAllocated = 4;
    mat->mProperties = calloc(mat->mNumAllocated, sizeof *mat->mProperties);
    if (!mat->mProperties) {
        free(mat);
        return NULL;
    }
    const char *name = "illum_baked";
    unsigned char sbuf[4 + 16];
    ai_uint32 len = (ai_uint32)strlen(name);
    memcpy(sbuf, &len, 4);
    memcpy(sbuf + 4, name, len + 1);
    int unlit = aiShadingMode_Unlit;
    float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    if (!add_property(mat, "?mat.name", aiPTI_String, sbuf, 4 + len + 1) ||
        !add_property(mat, "$mat.shadingm", aiPTI_Integer, &unlit, sizeof unlit) ||
        !add_property(mat, "$clr.diffuse", aiPTI_Float, white, sizeof white) ||
        !add_property(mat, "$clr.base", aiPTI_Float, white, sizeof white)) {
        free_material(mat);
        return NULL;
    }
    return mat;
}

static float clamp01(float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; }

static struct aiMesh *make_mesh(const il_bake_mesh *bm, float scale)
{
    struct aiMesh *m = calloc(1, sizeof *m);
    if (!m)
        return NULL;
    size_t nv = bm->num_vertices, nf = bm->num_triangles;
    m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    m->mNumVertices = bm->num_vertices;
    m->mNumFaces = bm->num_triangles;
    set_string(&m->mName, bm->name);
    m->mVertices = calloc(nv ? nv : 1, sizeof *m->mVertices);
    m->mNormals = calloc(nv ? nv : 1, sizeof *m->mNormals);
    m->mColors[0] = calloc(nv ? nv : 1, sizeof *m->mColors[0]);
    m->mColors[1] = calloc(nv ? nv : 1, sizeof *m->mColors[1]);
    m->mFaces = calloc(nf ? nf : 1, sizeof *m->mFaces);
    unsigned *idx = m->mFaces ? calloc(3 * (nf ? nf : 1), sizeof *idx) : NULL;
    if (!m->mVertices || !m->mNormals || !m->mColors[0] || !m->mColors[1] || !idx) {
        free(idx);
        free_mesh(m);
        return NULL;
    }
    m->mFaces[0].mIndices = idx;
    for (size_t v = 0; v < nv; v++) {
        const float *p = bm->positions + 3 * v;
        m->mVertices[v] = (struct aiVector3D){p[0], p[1], p[2]};
        if (bm->normals) {
            const float *n = bm->normals + 3 * v;
            m->mNormals[v] = (struct aiVector3D){n[0], n[1], n[2]};
        }
        if (bm->radiance) {
            const float *r = bm->radiance + 3 * v;
            float d[3];
            il_bake_display_rgb(r, scale, d);
            m->mColors[0][v] = (struct aiColor4D){clamp01(d[0]), clamp01(d[1]), clamp01(d[2]), 1.0f};
            m->mColors[1][v] = (struct aiColor4D){r[0], r[1], r[2], 1.0f};
        } else {
            m->mColors[0][v].a = m->mColors[1][v].a = 1.0f;
        }
    }
    for (size_t t = 0; t < nf; t++) {
        m->mFaces[t].mNumIndices = 3;
        m->mFaces[t].mIndices = idx + 3 * t;
        for (int k = 0; k < 3; k++)
            idx[3 * t + k] = bm->indices[3 * t + k];
    }
    return m;
}

static const struct aiMatrix4x4 identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* The aiScene of the bake, or NULL when out of memory. */
static struct aiScene *make_scene(const il_bake_result *bake, float scale)
{
    struct aiScene *sc = calloc(1, sizeof *sc);
    if (!sc)
        return NULL;
    uint32_t n = bake->num_meshes;
    sc->mRootNode = calloc(1, sizeof *sc->mRootNode);
    sc->mMeshes = calloc(n ? n : 1, sizeof *sc->mMeshes);
    sc->mMaterials = calloc(1, sizeof *sc->mMaterials);
    if (!sc->mRootNode || !sc->mMeshes || !sc->mMaterials) {
        free_scene(sc);
        return NULL;
    }
    set_string(&sc->mRootNode->mName, "illum_bake");
    sc->mRootNode->mTransformation = identity;
    if (!(sc->mMaterials[0] = make_material())) {
        free_scene(sc);
        return NULL;
    }
    sc->mNumMaterials = 1;
    sc->mRootNode->mChildren = calloc(n ? n : 1, sizeof *sc->mRootNode->mChildren);
    if (!sc->mRootNode->mChildren) {
        free_scene(sc);
        return NULL;
    }
    for (uint32_t i = 0; i < n; i++) {
        struct aiNode *node = calloc(1, sizeof *node);
        if (node) {
            sc->mRootNode->mChildren[sc->mRootNode->mNumChildren++] = node;
            node->mMeshes = malloc(sizeof *node->mMeshes);
        }
        if (!node || !node->mMeshes || !(sc->mMeshes[i] = make_mesh(&bake->meshes[i], scale))) {
            free_scene(sc);
            return NULL;
        }
        sc->mNumMeshes = i + 1;
        char name[80];
        snprintf(name, sizeof name, "%s", bake->meshes[i].name[0] ? bake->meshes[i].name : "mesh");
        set_string(&node->mName, name);
        node->mTransformation = identity;
        node->mParent = sc->mRootNode;
        node->mNumMeshes = 1;
        node->mMeshes[0] = i;
    }
    return sc;
}

il_status il_bake_write_gltf(const il_bake_result *bake, const char *path, float exposure,
                             bool binary, il_error *err)
{
    if (bake->num_meshes == 0)
        return il_fail(err, IL_ERR_INVALID, "%s: the bake has no mesh to write", path);
    struct aiScene *sc = make_scene(bake, exp2f(exposure));
    if (!sc)
        return il_fail(err, IL_ERR_MEMORY, "%s: out of memory building the glTF scene", path);
    /* assimp writes by file name: into the atomic file's temporary, which is
     * then renamed into place (il_atomic_close). */
    il_atomic_file af;
    il_status st = il_atomic_open(&af, path, err);
    if (st == IL_OK) {
        if (aiExportScene(sc, binary ? "glb2" : "gltf2", af.tmp, 0) != aiReturn_SUCCESS)
            st = il_fail(err, IL_ERR_RUNTIME, "%s: assimp could not export: %s", path,
                         aiGetErrorString());
        st = il_atomic_close(&af, st, err);
    }
    free_scene(sc);
    return st;
}
