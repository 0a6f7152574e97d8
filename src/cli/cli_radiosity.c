/* The radiosity options shared by `illum render --method radiosity` and
 * `illum bake`: parsing into an il_radiosity_desc, their help text, the
 * solver's progress line and the "radiosity" object of --stats JSON
 * (docs/radiosity.md lists every option, its default and range); and the
 * stats-file writer both commands use. */
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

const char cli_radiosity_help[] =
    "radiosity options (--method radiosity; docs/radiosity.md):\n"
    "  --patch-size METRES    largest patch edge (default: automatic, about 4,000\n"
    "                         patches over the scene)\n"
    "  --subdiv LEVELS        uniform subdivision instead, 1 to 10 levels; each splits\n"
    "                         every triangle or quad into 4\n"
    "  --form-factors auto|hemicube|raycast\n"
    "                         form-factor back-end (default auto: the hemicube while\n"
    "                         it has 4 pixels a patch, 49,152 patches at 256; raycast\n"
    "                         above)\n"
    "  --hemicube-res N       hemicube pixels along the top face, 8 to 4096 (default 256)\n"
    "  --ff-samples N         raycast: rays per patch, 1 to 16777216 (default 4096)\n"
    "  --solver shooting|jacobi|gauss-seidel\n"
    "                         progressive shooting (default) or gathering sweeps\n"
    "  --tolerance X          stop when unshot / initial power < X, above 0 to 1\n"
    "                         (default 0.01)\n"
    "  --max-steps N          at most N shots or sweeps (default: no limit)\n"
    "  --ff-cache-mb N        memory for cached form-factor rows, 1 to 1048576 MB\n"
    "                         (default 1024)\n"
    "  --adaptive THRESHOLD   after the first solve, split patches whose radiance\n"
    "                         differs from a neighbour's by more than this fraction\n"
    "                         and solve again (default: off)\n";

bool cli_radiosity_option(int argc, char **argv, int *i, cli_radiosity_options *o, int *rc)
{
    static const char *const names[] = {"--patch-size", "--subdiv",     "--form-factors",
                                        "--hemicube-res", "--ff-samples", "--solver",
                                        "--tolerance",  "--max-steps",  "--ff-cache-mb",
                                        "--adaptive"};
    const char *v = NULL;
    const char *name =
        cli_method_option(argc, argv, i, names, sizeof names / sizeof names[0], &o->note, &v);
    if (!name)
        return false;
    *rc = IL_EXIT_OK;
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    il_radiosity_desc *d = &o->desc;
    bool ok = true;
    double x;
    if (!strcmp(name, "--patch-size")) {
        ok = cli_parse_double(name, v, 1e-4, 1e4, &x);
        d->patch_size = (float)x;
    } else if (!strcmp(name, "--subdiv")) {
        ok = cli_parse_u32(name, v, 1, 10, &d->subdivisions);
    } else if (!strcmp(name, "--form-factors")) {
        if (!strcmp(v, "auto"))
            d->form_factors = IL_FF_AUTO;
        else if (!strcmp(v, "hemicube"))
            d->form_factors = IL_FF_HEMICUBE;
        else if (!strcmp(v, "raycast"))
            d->form_factors = IL_FF_RAYCAST;
        else {
            cli_error("--form-factors: expected auto, hemicube or raycast, got '%s'", v);
            ok = false;
        }
    } else if (!strcmp(name, "--hemicube-res")) {
        ok = cli_parse_u32(name, v, 8, 4096, &d->hemicube_resolution);
    } else if (!strcmp(name, "--ff-samples")) {
        ok = cli_parse_u32(name, v, 1, 1u << 24, &d->ray_samples);
    } else if (!strcmp(name, "--solver")) {
        if (!strcmp(v, "shooting"))
            d->solver = IL_SOLVER_SHOOTING;
        else if (!strcmp(v, "jacobi"))
            d->solver = IL_SOLVER_JACOBI;
        else if (!strcmp(v, "gauss-seidel"))
            d->solver = IL_SOLVER_GAUSS_SEIDEL;
        else {
            cli_error("--solver: expected shooting, jacobi or gauss-seidel, got '%s'", v);
            ok = false;
        }
    } else if (!strcmp(name, "--tolerance")) {
        /* 0 would mean "the default" to the library: refuse it here. */
        ok = cli_parse_double(name, v, 1e-9, 1.0, &x);
        d->tolerance = (float)x;
    } else if (!strcmp(name, "--max-steps")) {
        ok = cli_parse_u32(name, v, 1, UINT32_MAX, &d->max_steps);
    } else if (!strcmp(name, "--ff-cache-mb")) {
        ok = cli_parse_u32(name, v, 1, 1u << 20, &d->ff_cache_mb);
    } else if (!strcmp(name, "--adaptive")) {
        ok = cli_parse_double(name, v, 1e-6, 1e6, &x);
        d->adaptive_threshold = (float)x;
    }
    if (!ok)
        *rc = IL_EXIT_BAD_INPUT;
    return true;
}

/* "radiosity: step N, unshot X%" (a solve may take hundreds of thousands
 * of steps). */
static bool on_step(const il_radiosity_progress *p, void *user)
{
    cli_radiosity_options *o = user;
    return cli_solve_line_update(&o->line, p->seconds, false,
                                 "radiosity: step %u, unshot %.2f%%, %u patches, %.1fs", p->step,
                                 100.0 * p->unshot_fraction, p->num_patches, p->seconds);
}

void cli_radiosity_install_progress(cli_radiosity_options *o, bool quiet,
                                    const volatile sig_atomic_t *stop)
{
    cli_solve_line_start(&o->line, quiet, stop);
    o->desc.on_step = on_step;
    o->desc.on_step_user = o;
}

void cli_radiosity_end_progress(cli_radiosity_options *o) { cli_solve_line_end(&o->line); }

const char *cli_form_factor_name(il_form_factor_method m)
{
    return m == IL_FF_HEMICUBE ? "hemicube" : m == IL_FF_RAYCAST ? "raycast" : "auto";
}

void cli_radiosity_stats_json(cJSON *parent, const il_radiosity_stats *s)
{
    cJSON *r = cJSON_AddObjectToObject(parent, "radiosity");
    cJSON_AddNumberToObject(r, "patches", s->num_patches);
    cJSON_AddNumberToObject(r, "surfaces", s->num_surfaces);
    cJSON_AddNumberToObject(r, "steps", s->steps);
    cJSON_AddNumberToObject(r, "unshot_fraction", s->unshot_fraction);
    cJSON_AddNumberToObject(r, "view_fraction", s->view_fraction);
    cJSON_AddBoolToObject(r, "stalled", s->stalled);
    cJSON_AddStringToObject(r, "form_factors", cli_form_factor_name(s->form_factors));
    cJSON_AddNumberToObject(r, "seconds_mesh", s->seconds_mesh);
    cJSON_AddNumberToObject(r, "seconds_form_factors", s->seconds_form_factors);
    cJSON_AddNumberToObject(r, "seconds_solve", s->seconds_solve);
    cJSON_AddNumberToObject(r, "seconds_render", s->seconds_render);
    cJSON_AddNumberToObject(r, "rows_computed", (double)s->rows_computed);
    cJSON_AddNumberToObject(r, "cache_bytes", (double)s->cache_bytes);
    cJSON_AddNumberToObject(r, "peak_bytes", (double)s->peak_bytes);
}

void cli_radiosity_summary(const il_radiosity_stats *s)
{
    fprintf(stderr,
            "illum: radiosity: %u patches, %u steps, unshot %.3g%% (mesh %.2f s, form factors "
            "(%s) %.2f s, solve %.2f s, render %.2f s)\n",
            s->num_patches, s->steps, 100.0 * s->unshot_fraction, s->seconds_mesh,
            cli_form_factor_name(s->form_factors), s->seconds_form_factors, s->seconds_solve,
            s->seconds_render);
    if (s->stalled)
        fprintf(stderr,
                "illum: warning: radiosity: the solve stopped converging (unshot %.3g%% after %u "
                "steps): " CLI_NO_FINITE_SOLUTION "; the image shows the light of those steps\n",
                100.0 * s->unshot_fraction, s->steps);
}

bool cli_write_json(const char *path, cJSON *j)
{
    char *text = cJSON_Print(j);
    if (!text) {
        cli_error("%s: out of memory", path);
        return false;
    }
    size_t n = strlen(text);
    char *with_nl = cJSON_malloc(n + 2);
    bool ok = false;
    if (with_nl) {
        memcpy(with_nl, text, n);
        with_nl[n] = '\n';
        with_nl[n + 1] = '\0';
        ok = cli_write_text_atomic(path, with_nl);
        cJSON_free(with_nl);
    }
    cJSON_free(text);
    return ok;
}
