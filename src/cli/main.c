/* The `illum` program: dispatches to one file per sub-command. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/cli_mpi.h"
#include "core/lsan_suppressions.h"

static const char *usage =
    "illum " IL_VERSION_STRING " - global illumination\n"
    "\n"
    "usage: illum COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  render SCENE [options]   render a scene file or a built-in scene to an image\n"
    "  bake SCENE -o OUT.ply|OUT.glb [options]\n"
    "                           solve with (hierarchical) radiosity, write meshes with\n"
    "                           vertex radiance\n"
    "  illuminance SCENE --plane y=H | --points FILE | --surface NAME | --view\n"
    "                           light-meter readings in lux on a work plane, at points,\n"
    "                           over named surfaces, or in false colour on what the\n"
    "                           camera sees\n"
    "  sunhours SCENE --plane y=H | --points FILE --from T --latitude D --longitude D\n"
    "                           hours of direct sun on a plane or at points over a day\n"
    "  info SCENE               print what a scene contains\n"
    "  compare A B [--diff D]   compare two images (RMSE, relative MSE, luminance)\n"
    "  envmap convert IN OUT --to latlong|angular|cross\n"
    "                           resample an environment map into another mapping\n"
    "  tonemap IN OUT.png [--op linear|gamma|reinhard|filmic] [options]\n"
    "                           tone-map an HDR image (EXR, HDR, PFM) to a PNG\n"
    "  view SCENE [options]     interactive viewer (when built with IL_VIEWER)\n"
    "\n"
    "SCENE is a mesh file (OBJ, glTF/GLB, PLY, 3DS, any format assimp reads), a .json\n"
    "scene file (docs/scene-format.md) or a built-in name: cornell, atrium,\n"
    "simple-room, shadow-room, box-room, office, cornell-spheres.\n"
    "'illum COMMAND --help' (or 'illum help COMMAND') lists a command's options;\n"
    "'illum --version' prints the version.\n"
    "\n"
    "exit status: 0 success, 1 bad input (scene, file, option value), 2 usage error,\n"
    "             3 runtime failure, 4 compare: images differ more than allowed,\n"
    "             130 interrupted (the image rendered so far is written; a second\n"
    "                 Ctrl-C quits at once and writes nothing)\n";

int main(int argc, char **argv)
{
    if (argc < 2) {
        cli_error("no command given");
        fputs(usage, stderr);
        return IL_EXIT_USAGE;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        if (argc >= 3 && strcmp(cmd, "help") == 0) {
            char help[] = "--help";
            char *sub[] = {argv[2], help, NULL};
            if (!strcmp(argv[2], "render")) return cmd_render(2, sub);
            if (!strcmp(argv[2], "info")) return cmd_info(2, sub);
            if (!strcmp(argv[2], "illuminance")) return cmd_illuminance(2, sub);
            if (!strcmp(argv[2], "sunhours")) return cmd_sunhours(2, sub);
            if (!strcmp(argv[2], "compare")) return cmd_compare(2, sub);
            if (!strcmp(argv[2], "bake")) return cmd_bake(2, sub);
            if (!strcmp(argv[2], "envmap")) return cmd_envmap(2, sub);
            if (!strcmp(argv[2], "tonemap")) return cmd_tonemap(2, sub);
            if (!strcmp(argv[2], "view")) return cmd_view(2, sub);
            cli_error("unknown command '%s' (try 'illum --help')", argv[2]);
            return IL_EXIT_USAGE;
        }
        fputs(usage, stdout);
        return IL_EXIT_OK;
    }
    if (!strcmp(cmd, "--version") || !strcmp(cmd, "version")) {
        if (argc > 2) {
            cli_error("%s takes no argument ('%s')", cmd, argv[2]);
            return IL_EXIT_USAGE;
        }
        puts("illum " IL_VERSION_STRING);
        return IL_EXIT_OK;
    }
    if (!strcmp(cmd, "render")) {
        cli_mpi_init(&argc, &argv); /* MPI only under mpirun (docs/distributed.md) */
        return cli_mpi_finalize(cmd_render(argc - 1, argv + 1));
    }
    if (!strcmp(cmd, "info"))
        return cmd_info(argc - 1, argv + 1);
    if (!strcmp(cmd, "illuminance"))
        return cmd_illuminance(argc - 1, argv + 1);
    if (!strcmp(cmd, "sunhours"))
        return cmd_sunhours(argc - 1, argv + 1);
    if (!strcmp(cmd, "compare"))
        return cmd_compare(argc - 1, argv + 1);
    if (!strcmp(cmd, "bake"))
        return cmd_bake(argc - 1, argv + 1);
    if (!strcmp(cmd, "envmap"))
        return cmd_envmap(argc - 1, argv + 1);
    if (!strcmp(cmd, "tonemap"))
        return cmd_tonemap(argc - 1, argv + 1);
    if (!strcmp(cmd, "view"))
        return cmd_view(argc - 1, argv + 1);
    cli_error("unknown command '%s' (try 'illum --help')", cmd);
    return IL_EXIT_USAGE;
}
