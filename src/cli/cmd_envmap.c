/* `illum envmap convert IN OUT --to M`: resamples an environment map from
 * one mapping to another (il_envmap_convert; docs/environment.md). */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "image/envmap.h"

static const char *help =
    "usage: illum envmap convert IN OUT --to latlong|angular|cross [options]\n"
    "\n"
    "Resamples the environment map IN (.hdr .exr .pfm) into another mapping and\n"
    "writes OUT (by extension: .exr .hdr .pfm).  Each output texel is the\n"
    "solid-angle mean of IN over its footprint, so the light the map gives is kept.\n"
    "\n"
    "  --to M         the output's mapping: latlong (2:1), angular (a square light\n"
    "                 probe) or cross (a vertical cross, 3:4) (required)\n"
    "  --from M       IN's mapping (default: from its shape, 1:1 angular, 3:4 cross,\n"
    "                 else latlong)\n"
    "  --width W      OUT's width in texels (latlong: even; cross: a multiple of 3);\n"
    "                 default: about IN's texel density\n"
    "  --exr-float    write EXR as 32-bit float (default half)\n"
    "  --quiet        no summary line\n";

int cmd_envmap(int argc, char **argv)
{
    if (argc < 2) {
        cli_error("envmap: no action given (see 'illum envmap --help')");
        return IL_EXIT_USAGE;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        fputs(help, stdout);
        return IL_EXIT_OK;
    }
    if (strcmp(argv[1], "convert")) {
        cli_error("envmap: unknown action '%s' (available: convert; see 'illum envmap --help')", argv[1]);
        return IL_EXIT_USAGE;
    }
    const char *in = NULL, *out = NULL;
    il_env_mapping from = IL_ENV_LATLONG, to = IL_ENV_LATLONG;
    bool has_from = false, has_to = false, quiet = false;
    uint32_t width = 0;
    il_write_desc wd = {0};
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            return IL_EXIT_OK;
        } else if (!strcmp(a, "--to") || !strcmp(a, "--from")) {
            const char *v = cli_value(argc, argv, &i);
            if (!v)
                return IL_EXIT_USAGE;
            il_env_mapping m;
            if (!il_envmap_mapping_from_name(v, &m)) {
                cli_error("%s: expected latlong, angular or cross, got '%s'", a, v);
                return IL_EXIT_BAD_INPUT;
            }
            if (!strcmp(a, "--to")) {
                to = m;
                has_to = true;
            } else {
                from = m;
                has_from = true;
            }
        } else if (!strcmp(a, "--width")) {
            const char *v = cli_value(argc, argv, &i);
            if (!v)
                return IL_EXIT_USAGE;
            if (!cli_parse_u32(a, v, 1, 16384, &width))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--exr-float")) {
            wd.exr_precision = IL_EXR_FLOAT;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            quiet = true;
        } else if (a[0] == '-' && a[1] != '\0') {
            cli_error("envmap convert: unknown option '%s' (see 'illum envmap --help')", a);
            return IL_EXIT_USAGE;
        } else if (!in) {
            in = a;
        } else if (!out) {
            out = a;
        } else {
            cli_error("envmap convert: one input and one output ('%s' is extra)", a);
            return IL_EXIT_USAGE;
        }
    }
    if (!in || !out) {
        cli_error("envmap convert: needs IN and OUT (see 'illum envmap --help')");
        return IL_EXIT_USAGE;
    }
    if (!has_to) {
        cli_error("envmap convert: --to latlong|angular|cross is required");
        return IL_EXIT_USAGE;
    }
    int rc = cli_check_outputs(&out, 1);
    if (rc != IL_EXIT_OK)
        return rc;

    il_error err = {0};
    il_image src = {0}, dst = {0};
    il_status st = il_image_read(in, &src, &err);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    if (!has_from)
        from = il_envmap_mapping_for_size(src.width, src.height);
    st = il_envmap_convert(&src, from, to, width, &dst, &err);
    if (st != IL_OK) {
        cli_error("%s: %s", in, err.message);
    } else if ((st = il_image_write(&dst, out, &wd, &err)) != IL_OK) {
        cli_error("%s", err.message);
    } else if (!quiet) {
        fprintf(stderr, "illum: %s (%s %ux%u) -> %s (%s %ux%u)\n", in, il_envmap_mapping_name(from),
                src.width, src.height, out, il_envmap_mapping_name(to), dst.width, dst.height);
    }
    il_image_free(&src);
    il_image_free(&dst);
    return cli_exit_for(st);
}
