/* The run options render, view and bake share, parsed once so that the three
 * commands accept the same values (docs/cli.md): --seed, --threads, --quiet
 * and, for the commands that sample an image, --spp and --max-depth. */
#include <string.h>

#include "cli/cli.h"

/* il_render's own bound (src/methods/render.c). */
#define CLI_MAX_THREADS 4096u

bool cli_parse_exposure(const char *opt, const char *s, double *out)
{
    return cli_parse_double(opt, s, -50.0, 50.0, out);
}

bool cli_run_option(int argc, char **argv, int *i, il_render_desc *desc, cli_run_options *o, int *rc)
{
    const char *a = argv[*i];
    *rc = IL_EXIT_OK;
    if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
        o->quiet = true;
        return true;
    }
    bool sampling = !strcmp(a, "--spp") || !strcmp(a, "--max-depth");
    if (!(sampling && o->sampling) && strcmp(a, "--seed") && strcmp(a, "--threads"))
        return false;
    const char *v = cli_value(argc, argv, i);
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    bool ok;
    if (!strcmp(a, "--spp")) {
        ok = cli_parse_u32(a, v, 1, 1u << 24, &desc->spp);
    } else if (!strcmp(a, "--max-depth")) {
        ok = cli_parse_u32(a, v, 1, 1024, &desc->max_depth);
    } else if (!strcmp(a, "--seed")) {
        ok = cli_parse_u64(a, v, &desc->seed);
        o->has_seed = ok;
    } else {
        uint32_t t = 0;
        ok = cli_parse_u32(a, v, 1, CLI_MAX_THREADS, &t);
        if (ok)
            desc->threads = (int)t;
    }
    if (!ok)
        *rc = IL_EXIT_BAD_INPUT;
    return true;
}

int cli_run_apply_settings(const char *scene_path, const il_render_settings *rs, bool method_given,
                           const cli_run_options *o, il_render_desc *desc)
{
    il_method method = IL_METHOD_PT;
    if (rs->method[0] && !cli_method_from_name(rs->method, &method)) {
        cli_error("%s: unknown method '%s' in the render settings (available: " CLI_METHOD_NAMES ")",
                  scene_path, rs->method);
        return IL_EXIT_BAD_INPUT;
    }
    if (rs->method[0] && !method_given)
        desc->method = method;
    if (desc->max_depth == 0)
        desc->max_depth = rs->max_depth;
    if (!o->has_seed)
        desc->seed = rs->seed;
    return IL_EXIT_OK;
}
