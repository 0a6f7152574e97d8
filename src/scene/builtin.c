/* Built-in scenes by name: il_builtin_exists / il_builtin_load. */
#include "scene/builtin.h"

#include <string.h>

#include "core/error.h"

typedef struct builtin_entry {
    const char *name;
    il_status (*build)(il_scene *scene, il_error *err);
} builtin_entry;

static const builtin_entry builtins[] = {
    {"cornell", il_builtin_cornell},
    {"atrium", il_builtin_atrium},
    {"simple-room", il_builtin_simple_room},
    {"shadow-room", il_builtin_shadow_room},
    {"box-room", il_builtin_box_room},
    {"office", il_builtin_office},
    {"cornell-spheres", il_builtin_cornell_spheres},
};

static const builtin_entry *find_builtin(const char *name)
{
    if (!name)
        return NULL;
    for (size_t i = 0; i < sizeof builtins / sizeof builtins[0]; i++)
        if (strcmp(name, builtins[i].name) == 0)
            return &builtins[i];
    return NULL;
}

bool il_builtin_exists(const char *name)
{
    return find_builtin(name) != NULL;
}

il_status il_builtin_load(il_scene *scene, const char *name, il_error *err)
{
    const builtin_entry *b = find_builtin(name);
    if (!b)
        return il_fail(err, IL_ERR_INVALID, "'%s' is not a built-in scene (cornell, atrium, simple-room, "
                       "shadow-room, box-room, office, cornell-spheres)",
                       name ? name : "(null)");
    return b->build(scene, err);
}
