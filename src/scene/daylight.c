/* il_scene_set_daylight: a sky for a daylight study set as the scene's
 * environment, and its sun as a directional light that belongs to it: the
 * next il_scene_set_environment removes the sun with the sky
 * (docs/environment.md#skies). */
#include "core/color.h"
#include "core/error.h"
#include "image/sky.h"
#include "illum/illum.h"
#include "scene/scene.h"

il_status il_scene_set_daylight(il_scene *scene, const il_sky_desc *desc, il_error *err)
{
    if (!scene || !desc)
        return il_fail(err, IL_ERR_INVALID, "daylight: no scene or no sky");
    il_image sky = {0};
    il_status st = desc->cie_type == 0 ? il_sky_overcast(desc, &sky, err) : il_sky_cie(desc, &sky, err);
    if (st != IL_OK)
        return st;
    st = il_scene_set_environment(scene, &(il_environment_desc){.map = &sky, .mapping = IL_ENV_LATLONG}, err);
    il_image_free(&sky);
    if (st != IL_OK)
        return st;
    scene->has_daylight = true;
    scene->daylight = il_sky_with_defaults(desc);
    if (!(desc->sun_normal_lux > 0.0))
        return IL_OK;
    /* il_sky_cie has checked the sun's position and illuminance. */
    il_vec3 towards = il_sky_direction(desc->sun_altitude, desc->sun_azimuth, desc->north);
    float e = (float)(desc->sun_normal_lux / IL_LUMENS_PER_WATT);
    double diameter = scene->daylight.sun_diameter;
    il_light_desc sun = {.type = IL_LIGHT_DIRECTIONAL,
                         .direction = {-towards.x, -towards.y, -towards.z},
                         .intensity = {e, e, e},
                         .diameter = diameter > 0.0 ? (float)diameter : 0.0f};
    if ((st = il_scene_add_light(scene, &sun, err)) != IL_OK)
        return st;
    scene->has_sky_sun = true;
    scene->sky_sun = scene->num_user_lights - 1;
    return IL_OK;
}

bool il_scene_get_daylight(const il_scene *scene, il_sky_desc *out)
{
    if (!scene || !scene->has_daylight)
        return false;
    if (out)
        *out = scene->daylight;
    return true;
}
