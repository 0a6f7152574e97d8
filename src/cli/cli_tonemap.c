/* The tone-mapping options shared by `illum render` (for its PNG outputs) and
 * `illum tonemap`: parsing into an il_tonemap_desc and their help text
 * (docs/tonemapping.md explains each operator; docs/cli.md lists the
 * options, defaults and ranges). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

const char cli_tonemap_help[] =
    "\ntone mapping (PNG outputs only; docs/tonemapping.md):\n"
    "  --tonemap linear|gamma|reinhard|filmic\n"
    "                         operator (default linear: clamp + sRGB; gamma: a\n"
    "                         plain power 1/G; reinhard: Reinhard et al. 2002 with\n"
    "                         a white point; filmic: the ACES fit of Narkowicz)\n"
    "  --auto-exposure [P]    scale so that the P-th percentile of the luminance of\n"
    "                         the non-black pixels maps to 1 (P 0.001 to 100,\n"
    "                         default 99), on top of --exposure\n"
    "  --gamma G              gamma operator: exponent 1/G (0.01 to 100, default 2.2)\n"
    "  --white W              reinhard: luminance after exposure that maps to white\n"
    "                         (default: the image's largest)\n"
    "  --bloom K              move the fraction K (0 to 1) of the light above the\n"
    "                         threshold into an energy-preserving glare (default 0)\n"
    "  --bloom-threshold T    luminance after exposure where glare starts (default 1)\n"
    "  --bloom-radius R       glare spread, fraction of the image diagonal\n"
    "                         (0.0001 to 1, default 0.02)\n";

static bool op_from_name(const char *name, il_tonemap_op *op)
{
    static const struct {
        const char *name;
        il_tonemap_op op;
    } ops[] = {{"linear", IL_TONEMAP_LINEAR},
               {"gamma", IL_TONEMAP_GAMMA},
               {"reinhard", IL_TONEMAP_REINHARD},
               {"filmic", IL_TONEMAP_FILMIC}};
    for (size_t k = 0; k < sizeof ops / sizeof ops[0]; k++)
        if (!strcmp(name, ops[k].name)) {
            *op = ops[k].op;
            return true;
        }
    return false;
}

/* Whether s is a number (so "--auto-exposure 95" takes it as the percentile). */
static bool is_number(const char *s)
{
    char *end = NULL;
    errno = 0;
    (void)strtod(s, &end);
    return end != s && *end == '\0';
}

static bool parse_float(const char *opt, const char *v, double min, double max, float *out)
{
    double x;
    if (!cli_parse_double(opt, v, min, max, &x))
        return false;
    *out = (float)x;
    return true;
}

bool cli_tonemap_option(int argc, char **argv, int *i, bool op_alias, cli_tonemap_options *o,
                        int *rc)
{
    const char *a = argv[*i];
    il_tonemap_desc *d = &o->desc;
    *rc = IL_EXIT_OK;
    if (!strcmp(a, "--auto-exposure")) {
        o->given = true;
        d->auto_exposure = true;
        if (*i + 1 < argc && is_number(argv[*i + 1])) {
            (*i)++;
            if (!parse_float(a, argv[*i], 0.001, 100.0, &d->auto_percentile))
                *rc = IL_EXIT_BAD_INPUT;
        }
        return true;
    }
    bool known = !strcmp(a, "--tonemap") || (op_alias && !strcmp(a, "--op")) ||
                 !strcmp(a, "--gamma") || !strcmp(a, "--white") || !strcmp(a, "--bloom") ||
                 !strcmp(a, "--bloom-threshold") || !strcmp(a, "--bloom-radius");
    if (!known)
        return false;
    const char *v = cli_value(argc, argv, i);
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    o->given = true;
    bool ok = true;
    if (!strcmp(a, "--tonemap") || !strcmp(a, "--op")) {
        if (!op_from_name(v, &d->op)) {
            cli_error("%s: unknown operator '%s' (available: linear, gamma, reinhard, filmic)", a,
                      v);
            ok = false;
        }
    } else if (!strcmp(a, "--gamma")) {
        ok = parse_float(a, v, 0.01, 100.0, &d->gamma);
        o->gamma_opt = a;
    } else if (!strcmp(a, "--white")) {
        /* Zero means "the image's largest" to the library: leave it out for that. */
        ok = parse_float(a, v, 1e-9, 1e30, &d->white);
        o->white_opt = a;
    } else if (!strcmp(a, "--bloom")) {
        ok = parse_float(a, v, 0.0, 1.0, &d->bloom);
    } else if (!strcmp(a, "--bloom-threshold")) {
        ok = parse_float(a, v, 1e-9, 1e30, &d->bloom_threshold);
    } else if (!strcmp(a, "--bloom-radius")) {
        ok = parse_float(a, v, 1e-4, 1.0, &d->bloom_radius);
    }
    *rc = ok ? IL_EXIT_OK : IL_EXIT_BAD_INPUT;
    return true;
}

int cli_tonemap_check(const char *command, const cli_tonemap_options *o)
{
    if (o->gamma_opt && o->desc.op != IL_TONEMAP_GAMMA) {
        cli_error("%s: --gamma sets the gamma operator's exponent; it needs --tonemap gamma",
                  command);
        return IL_EXIT_USAGE;
    }
    if (o->white_opt && o->desc.op != IL_TONEMAP_REINHARD) {
        cli_error("%s: --white sets Reinhard's white point; it needs --tonemap reinhard", command);
        return IL_EXIT_USAGE;
    }
    return IL_EXIT_OK;
}

const il_tonemap_desc *cli_tonemap_desc(cli_tonemap_options *o, float exposure)
{
    if (!o->given)
        return NULL;
    o->desc.exposure = exposure;
    return &o->desc;
}
