/* The hierarchical-radiosity options shared by `illum render --method hr`
 * and `illum bake --method hr`: parsing into an il_hr_desc, their help
 * text, the "hr" object of --stats JSON and the summary line
 * (docs/hierarchical-radiosity.md lists every option, its default and
 * range). */
#include <stdio.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "cli/cli.h"

const char cli_hr_help[] =
    "hierarchical radiosity options (--method hr; docs/hierarchical-radiosity.md):\n"
    "  --bf-eps X             refine a link while F * B * V / B_ref > X, B_ref the\n"
    "                         scene's mean emitted radiance, 1e-7 to 1 (default\n"
    "                         0.015, SPLASH-2's BF epsilon)\n"
    "  --area-eps X           ... and the larger element's area > X * (the scene's\n"
    "                         bounding-box diagonal)^2, 1e-9 to 1 (default 6.92e-4,\n"
    "                         SPLASH-2's 2000 in a room about 1700 units wide)\n"
    "  --energy-eps X         stop when what is left of the reflected energy,\n"
    "                         estimated from its last changes, < X of it, 1e-9\n"
    "                         to 1 (default 0.005)\n"
    "  --vis-rays N           visibility rays per link, 1 to 4096 (default 16; with\n"
    "                         16, 64, 256, ... a link may settle after 4)\n"
    "  --max-iterations N     at most N iterations, each a refinement and then\n"
    "                         gather + push-pull sweeps, 1 to 100000 (default 100)\n";

bool cli_hr_option(int argc, char **argv, int *i, cli_hr_options *o, int *rc)
{
    static const char *const names[] = {"--bf-eps", "--area-eps", "--energy-eps", "--vis-rays",
                                        "--max-iterations"};
    const char *v = NULL;
    const char *name =
        cli_method_option(argc, argv, i, names, sizeof names / sizeof names[0], &o->note, &v);
    if (!name)
        return false;
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    il_hr_desc *d = &o->desc;
    bool ok = true;
    double x = 0.0;
    /* Zero means "the default" to the library, so the lower bounds are above 0. */
    if (!strcmp(name, "--bf-eps")) {
        ok = cli_parse_double(name, v, 1e-7, 1.0, &x);
        d->bf_eps = (float)x;
    } else if (!strcmp(name, "--area-eps")) {
        ok = cli_parse_double(name, v, 1e-9, 1.0, &x);
        d->area_eps = (float)x;
    } else if (!strcmp(name, "--energy-eps")) {
        ok = cli_parse_double(name, v, 1e-9, 1.0, &x);
        d->energy_eps = (float)x;
    } else if (!strcmp(name, "--vis-rays")) {
        ok = cli_parse_u32(name, v, 1, 4096, &d->vis_rays);
    } else if (!strcmp(name, "--max-iterations")) {
        ok = cli_parse_u32(name, v, 1, 100000, &d->max_iterations);
    }
    *rc = ok ? IL_EXIT_OK : IL_EXIT_BAD_INPUT;
    return true;
}

/* "hr: linking patches N / M", "hr: iteration K: refining ...", "hr:
 * iteration K done, energy change X%" (the test against --energy-eps). */
static bool on_step(const il_hr_progress *p, void *user)
{
    cli_hr_options *o = user;
    cli_solve_line *l = &o->line;
    switch (p->phase) {
    case IL_HR_LINKING:
        return cli_solve_line_update(l, p->seconds, false, "hr: linking patches %u / %u, %.1fs",
                                     p->roots_done, p->num_roots, p->seconds);
    case IL_HR_REFINING:
        return cli_solve_line_update(l, p->seconds, false,
                                     "hr: iteration %u: refining patches %u / %u, %.1fs",
                                     p->iterations + 1, p->roots_done, p->num_roots, p->seconds);
    case IL_HR_ITERATED:
    default:
        return cli_solve_line_update(l, p->seconds, false,
                                     "hr: iteration %u done, energy change %.3g%%, %.1fs",
                                     p->iterations, 100.0 * p->energy_change, p->seconds);
    }
}

void cli_hr_install_progress(cli_hr_options *o, bool quiet, const volatile sig_atomic_t *stop)
{
    cli_solve_line_start(&o->line, quiet, stop);
    o->desc.on_step = on_step;
    o->desc.on_step_user = o;
}

void cli_hr_end_progress(cli_hr_options *o) { cli_solve_line_end(&o->line); }

void cli_hr_stats_json(cJSON *parent, const il_hr_stats *s)
{
    cJSON *r = cJSON_AddObjectToObject(parent, "hr");
    cJSON_AddNumberToObject(r, "patches", s->patches);
    cJSON_AddNumberToObject(r, "elements", (double)s->elements);
    cJSON_AddNumberToObject(r, "leaves", (double)s->leaves);
    cJSON_AddNumberToObject(r, "links", (double)s->links);
    cJSON_AddNumberToObject(r, "iterations", s->iterations);
    cJSON_AddNumberToObject(r, "sweeps", s->sweeps);
    cJSON_AddNumberToObject(r, "visibility_rays", (double)s->visibility_rays);
    cJSON_AddNumberToObject(r, "seconds_setup", s->seconds_setup);
    cJSON_AddNumberToObject(r, "seconds_refine", s->seconds_refine);
    cJSON_AddNumberToObject(r, "seconds_gather", s->seconds_gather);
    cJSON_AddNumberToObject(r, "seconds_average", s->seconds_average);
    cJSON_AddNumberToObject(r, "seconds_render", s->seconds_render);
    cJSON_AddNumberToObject(r, "peak_bytes", (double)s->peak_bytes);
    cJSON_AddBoolToObject(r, "stopped", s->stopped);
    cJSON_AddBoolToObject(r, "converged", s->converged);
    cJSON_AddBoolToObject(r, "stalled", s->stalled);
    cJSON_AddNumberToObject(r, "energy_change", s->energy_change);
}

void cli_hr_summary(const il_hr_stats *s)
{
    fprintf(stderr,
            "illum: hr: %u patches, %llu elements, %llu links, %u iterations, %u sweeps, %llu visibility "
            "rays (setup %.2f s, refine %.2f s, gather %.2f s, average %.2f s, render %.2f s, "
            "%.1f MB)\n",
            s->patches, (unsigned long long)s->elements, (unsigned long long)s->links,
            s->iterations, s->sweeps, (unsigned long long)s->visibility_rays, s->seconds_setup,
            s->seconds_refine, s->seconds_gather, s->seconds_average, s->seconds_render,
            (double)s->peak_bytes / (1024.0 * 1024.0));
    if (s->stalled)
        fprintf(stderr,
                "illum: warning: hr: the solve stopped converging (%u iteration%s, %u sweeps): "
                CLI_NO_FINITE_SOLUTION "; the image shows the light of those sweeps\n",
                s->iterations, s->iterations == 1 ? "" : "s", s->sweeps);
    else if (!s->converged && !s->stopped)
        fprintf(stderr,
                "illum: warning: hr: not converged after %u iteration%s (the energy still changed "
                "by %.3g%%): raise --max-iterations\n",
                s->iterations, s->iterations == 1 ? "" : "s", 100.0 * s->energy_change);
}
