/* `illum info SCENE`: what was loaded. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

static const char *help =
    "usage: illum info SCENE [--quiet]\n"
    "       illum info --devices\n"
    "\n"
    "Loads SCENE (a file or a built-in name), validates it and prints the counts\n"
    "of meshes, triangles, materials, lights, the bounds, the camera and every\n"
    "warning raised while loading.  A scene that loads but cannot be rendered (no\n"
    "light, no valid triangle) is still described, then the reason is given and\n"
    "the exit status is 1.  --devices lists the compute devices instead:\n"
    "the CPU and each CUDA GPU (name, memory, compute capability, driver), or why\n"
    "there is none.\n";

int cmd_info(int argc, char **argv)
{
    const char *path = NULL;
    bool quiet = false;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(help, stdout);
            return IL_EXIT_OK;
        } else if (!strcmp(argv[i], "--devices")) {
            return cli_devices_list();
        } else if (!strcmp(argv[i], "--quiet")) {
            quiet = true;
        } else {
            int rc = cli_scene_argument("info", argv[i], &path);
            if (rc != IL_EXIT_OK)
                return rc;
        }
    }
    if (cli_require_scene("info", path) != IL_EXIT_OK)
        return IL_EXIT_USAGE;
    /* Loaded and committed here rather than by cli_load_scene, so that a
     * scene that loads but cannot be rendered is still described. */
    il_scene *scene = NULL;
    il_error err = {0};
    il_load_desc ld = {0}; /* warnings are listed below */
    il_status st = il_scene_load(path, &ld, &scene, &err);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    il_error commit_err = {0};
    il_status commit_st = il_scene_commit(scene, &commit_err);
    (void)quiet;
    il_scene_info in;
    il_scene_get_info(scene, &in);
    il_camera_desc cam;
    bool has_camera = il_scene_get_camera(scene, &cam);
    printf("scene:      %s\n", path);
    printf("meshes:     %u\n", in.num_meshes);
    printf("triangles:  %llu (%llu emissive, %llu dropped)\n", (unsigned long long)in.num_triangles,
           (unsigned long long)in.num_emissive_triangles, (unsigned long long)in.dropped_triangles);
    printf("materials:  %u (including the default)\n", in.num_materials);
    printf("textures:   %u\n", in.num_textures);
    if (in.num_panes)
        printf("panes:      %u mesh%s of thin_glass (window panes: light passes them on a straight line)\n",
               in.num_panes, in.num_panes == 1 ? "" : "es");
    printf("lights:     %u point/spot/directional, %llu emissive triangles%s\n", in.num_lights,
           (unsigned long long)in.num_emissive_triangles, in.has_environment ? ", environment" : "");
    if (in.num_portal_triangles)
        printf("portals:    %u triangle%s, %.3g m^2 (the environment's light is sampled through them)\n",
               in.num_portal_triangles, in.num_portal_triangles == 1 ? "" : "s", (double)in.portal_area);
    else if (in.num_panes && in.has_environment)
        printf("portals:    none (a portal on each window makes a room lit by the sky less noisy: "
               "docs/scene-format.md, \"environment\")\n");
    il_sky_desc sky;
    if (il_scene_get_daylight(scene, &sky)) {
        if (sky.cie_type == 0)
            printf("sky:        CIE overcast, %g lx horizontal\n", sky.horizontal_lux);
        else if (sky.sun_normal_lux > 0.0) {
            double azimuth = fmod(sky.sun_azimuth, 360.0);
            printf("sky:        CIE type %d, %g lx horizontal; sun at %.2f altitude, %.2f azimuth (north %g), "
                   "%.0f lx normal, %g degrees across\n",
                   sky.cie_type, sky.horizontal_lux, sky.sun_altitude, azimuth < 0.0 ? azimuth + 360.0 : azimuth,
                   sky.north, sky.sun_normal_lux, sky.sun_diameter > 0.0 ? sky.sun_diameter : 0.0);
        } else
            printf("sky:        CIE type %d, %g lx horizontal; no direct sun\n", sky.cie_type, sky.horizontal_lux);
    }
    printf("bounds:     (%g, %g, %g) .. (%g, %g, %g)\n", (double)in.bounds_min.x,
           (double)in.bounds_min.y, (double)in.bounds_min.z, (double)in.bounds_max.x,
           (double)in.bounds_max.y, (double)in.bounds_max.z);
    if (has_camera)
        printf("camera:     position (%g, %g, %g) target (%g, %g, %g) up (%g, %g, %g) fov %g\n",
               (double)cam.position.x, (double)cam.position.y, (double)cam.position.z,
               (double)cam.target.x, (double)cam.target.y, (double)cam.target.z, (double)cam.up.x,
               (double)cam.up.y, (double)cam.up.z, (double)cam.fov_y);
    else
        printf("camera:     none\n");
    printf("warnings:   %u\n", in.num_warnings);
    for (uint32_t i = 0; i < in.num_warnings; i++)
        printf("  warning: %s\n", il_scene_warning(scene, i));
    il_scene_release(scene);
    if (commit_st != IL_OK) {
        fflush(stdout);
        cli_error("%s: %s", path, commit_err.message);
        return cli_exit_for(commit_st);
    }
    return IL_EXIT_OK;
}
