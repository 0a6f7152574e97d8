/* Built-in scenes, selectable by name with no file. */
#ifndef IL_SCENE_BUILTIN_H
#define IL_SCENE_BUILTIN_H

#include <stdbool.h>
#include "illum/illum.h"

/* True when `name` is a built-in scene ("cornell", "atrium", "simple-room",
 * "shadow-room", "box-room", "office", "cornell-spheres"). */
bool il_builtin_exists(const char *name);
/* Fills an empty scene with the built-in scene of that name. */
il_status il_builtin_load(il_scene *scene, const char *name, il_error *err);

/* The Cornell box from the published measurements, in metres, reflectances
 * and light spectrum converted to linear Rec.709 through the CIE 1931
 * colour-matching functions, with the published camera. */
il_status il_builtin_cornell(il_scene *scene, il_error *err);
/* The same box with a mirror sphere and a glass sphere instead of the
 * blocks (the caustics scene of photon mapping). */
il_status il_builtin_cornell_spheres(il_scene *scene, il_error *err);
/* A two-storey arcaded courtyard, about 250,000 triangles, sun + lamps. */
il_status il_builtin_atrium(il_scene *scene, il_error *err);
/* The radiosity rooms (builtin_rooms.c, docs/builtin-scenes.md): a 4 x 3 x 4 m
 * room with a red left and a green right wall lit by its whole ceiling; the
 * same with a slab at half height; a room with a quarter-ceiling lamp and
 * four coloured boxes. */
il_status il_builtin_simple_room(il_scene *scene, il_error *err);
il_status il_builtin_shadow_room(il_scene *scene, il_error *err);
il_status il_builtin_box_room(il_scene *scene, il_error *err);
/* The furnished office for hierarchical radiosity (builtin_office.c): an
 * 8 x 3 x 6 m room of 537 rectangles with desks, chairs, shelves, books, a
 * partition and six ceiling lamps. */
il_status il_builtin_office(il_scene *scene, il_error *err);

#endif
