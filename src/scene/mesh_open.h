/* Whether a triangle mesh is open: a surface with a border, such as a
 * window modelled as one sheet, rather than the closed boundary of a solid. */
#ifndef IL_SCENE_MESH_OPEN_H
#define IL_SCENE_MESH_OPEN_H

#include <stdbool.h>
#include <stdint.h>
#include "core/error.h"

/* True in *open when some edge belongs to one triangle only.  Vertices are
 * matched by position, to a millionth of the mesh's size (a closed box with
 * per-face normals repeats its corners, a sphere's poles are computed once
 * per segment), so only the geometry counts.  positions: 3 floats per vertex;
 * indices: 3 per triangle, each below num_vertices. */
il_status il_mesh_is_open(const float *positions, uint32_t num_vertices, const uint32_t *indices,
                          uint32_t num_triangles, bool *open, il_error *err);

#endif
