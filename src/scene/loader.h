/* Scene file loaders; il_scene_load (load.c) picks one by name or extension. */
#ifndef IL_SCENE_LOADER_H
#define IL_SCENE_LOADER_H

#include <stddef.h>
#include "illum/illum.h"

/* Any format assimp reads (OBJ+MTL, glTF/GLB, PLY, 3DS, ...), into an existing scene.
 * `transform` is an optional column-major 4x4 matrix applied to positions
 * and normals (NULL: identity); `material_override` (0: none) replaces every
 * material of the file. */
il_status il_load_assimp(il_scene *scene, const char *path, const float *transform,
                         uint32_t material_override, il_error *err);
/* A JSON scene file (docs/scene-format.md). */
il_status il_load_json(il_scene *scene, const char *path, il_error *err);

/* Looks up a replacement for a file's material by its name: a scene material
 * index, or 0 to convert the file's own material. */
typedef uint32_t (*il_material_lookup_fn)(const char *name, void *user);

typedef struct il_assimp_options {
    const float *transform;            /* column-major 4x4; NULL: identity */
    uint32_t material_override;        /* 0: none, else replaces every material */
    il_material_lookup_fn lookup;      /* optional, asked per file material */
    void *lookup_user;
} il_assimp_options;

/* il_load_assimp with every option; `opt` may be NULL. */
il_status il_load_assimp_ex(il_scene *scene, const char *path, const il_assimp_options *opt,
                            il_error *err);

/* A PLY file's header and its element and list counts against its size
 * (ply_check.c): IL_ERR_FORMAT naming the file when a header line is not
 * PLY or a count is more than the rest of the file can hold (assimp would
 * allocate for it first, or loop); IL_OK otherwise, also when a binary
 * body merely ends early (assimp reports that). */
il_status il_ply_check(const char *path, il_error *err);

/* An OFF file's vertex and face counts against its size (off_check.c):
 * IL_ERR_FORMAT naming the file when the rest of it cannot hold them
 * (assimp would reserve gigabytes first); IL_OK otherwise. */
il_status il_off_check(const char *path, il_error *err);

/* A glTF 2.0 file's GLB layout, JSON and byte ranges (buffers,
 * bufferViews, accessors) against the spec and the bytes it holds
 * (gltf_check.c): IL_ERR_FORMAT naming the file and what is wrong (assimp
 * would read past a buffer or allocate what the file claims); IL_OK
 * otherwise. */
il_status il_gltf_check(const char *path, il_error *err);

/* The first key that appears twice in one object anywhere in the JSON
 * value j (cJSON keeps both, and every lookup finds the first), or NULL
 * (load_json.c; the scene files and the command line's camera files). */
struct cJSON;
const char *il_json_duplicate_key(const struct cJSON *j);

/* Reads a whole file into a NUL-terminated buffer (free() it); IL_ERR_IO naming
 * the file when it cannot be read. */
il_status il_load_read_file(const char *path, char **out, size_t *size, il_error *err);

/* Rewrites err's message (from il_scene_add_* and the like) as
 * "FILE: WHERE: message" (WHERE may be NULL); returns status. */
il_status il_load_prefix_error(il_error *err, il_status status, const char *file, const char *where);

/* Adds a mesh after applying x to its positions and normals (normals by the
 * inverse transpose); a mirroring x (negative determinant) also reverses the
 * winding so the front face stays the front. */
struct il_xform;
il_status il_load_add_mesh(il_scene *scene, const il_mesh_desc *d, const struct il_xform *x,
                           il_error *err);

/* Simple shapes for JSON scenes (load_shapes.c), centred at the origin,
 * counter-clockwise seen from outside.  Arrays are malloc'ed: il_shape_free. */
typedef struct il_shape_mesh {
    uint32_t num_vertices, num_triangles;
    float *positions, *normals, *uvs; /* normals NULL for flat shapes */
    uint32_t *indices;
} il_shape_mesh;

/* A quad in the xz-plane, sx by sz, facing +y. */
il_status il_shape_quad(float sx, float sz, il_shape_mesh *out, il_error *err);
/* An axis-aligned box sx by sy by sz, faces outward, flat. */
il_status il_shape_box(float sx, float sy, float sz, il_shape_mesh *out, il_error *err);
/* A UV sphere: `segments` around the equator (>= 3), segments/2 rings, smooth normals. */
il_status il_shape_sphere(float radius, uint32_t segments, il_shape_mesh *out, il_error *err);
/* Reverses every triangle and normal (faces inward). */
void il_shape_flip(il_shape_mesh *m);
void il_shape_free(il_shape_mesh *m);

#endif
