/* `illum tonemap IN OUT.png`: an HDR image to a display PNG through one of
 * the tone-mapping operators (docs/tonemapping.md). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "image/tonemap.h"

static const char *help =
    "usage: illum tonemap IN.{exr,hdr,pfm} OUT.png [options]\n"
    "\n"
    "Maps the radiance of IN (an EXR, Radiance HDR or PFM file; PNG and JPEG are\n"
    "read too, as linear values) to display values and writes OUT as an 8-bit\n"
    "sRGB PNG.  The steps: NaN/Inf pixels become black, exposure (manual and\n"
    "automatic), bloom, the operator's curve, the transfer function.\n"
    "\n"
    "  --op OP                the same as --tonemap OP (below)\n"
    "  --exposure EV          scale by 2^EV first (-50 to 50, default 0)\n"
    "  --quiet, -q            no summary line\n";

static bool is_png(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    return dot && !strcasecmp(dot, ".png");
}

static const char *op_name(il_tonemap_op op)
{
    switch (op) {
    case IL_TONEMAP_LINEAR: return "linear";
    case IL_TONEMAP_GAMMA: return "gamma";
    case IL_TONEMAP_REINHARD: return "reinhard";
    case IL_TONEMAP_FILMIC: return "filmic";
    }
    return "?";
}

int cmd_tonemap(int argc, char **argv)
{
    const char *in_path = NULL, *out_path = NULL;
    cli_tonemap_options tm = {0};
    double exposure = 0.0;
    bool quiet = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int rc;
        if (cli_tonemap_option(argc, argv, &i, true, &tm, &rc)) {
            if (rc != IL_EXIT_OK)
                return rc;
        } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(help, stdout);
            fputs(cli_tonemap_help, stdout);
            return IL_EXIT_OK;
        } else if (!strcmp(a, "--exposure")) {
            const char *v = cli_value(argc, argv, &i);
            if (!v)
                return IL_EXIT_USAGE;
            if (!cli_parse_exposure(a, v, &exposure))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            quiet = true;
        } else if (a[0] == '-' && a[1] != '\0') {
            cli_error("tonemap: unknown option '%s' (see 'illum tonemap --help')", a);
            return IL_EXIT_USAGE;
        } else if (!in_path) {
            in_path = a;
        } else if (!out_path) {
            out_path = a;
        } else {
            cli_error("tonemap: one input and one output ('%s' is extra)", a);
            return IL_EXIT_USAGE;
        }
    }
    if (!in_path || !out_path) {
        cli_error("tonemap: needs an input image and an output PNG (see 'illum tonemap --help')");
        return IL_EXIT_USAGE;
    }
    int rc = cli_tonemap_check("tonemap", &tm);
    if (rc != IL_EXIT_OK)
        return rc;
    if (!is_png(out_path)) {
        cli_error("%s: tonemap writes display values as PNG; use a .png output (HDR formats keep "
                  "radiance: see 'illum render -o')", out_path);
        return IL_EXIT_BAD_INPUT;
    }
    if ((rc = cli_check_outputs(&out_path, 1)) != IL_EXIT_OK)
        return rc;

    il_error err = {0};
    il_image img = {0};
    il_status st = il_image_read(in_path, &img, &err);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    /* Always through the operator, linear included: a pixel with a NaN or
     * Inf channel is black as a whole (docs/tonemapping.md). */
    tm.given = true;
    il_write_desc wd = {.tonemap = cli_tonemap_desc(&tm, (float)exposure)};
    double auto_lum = 0.0;
    if (tm.desc.auto_exposure && !quiet)
        auto_lum = il_luminance_percentile(
            &img, tm.desc.auto_percentile > 0.0f ? tm.desc.auto_percentile : 99.0);
    st = il_image_write(&img, out_path, &wd, &err);
    il_image_free(&img);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    if (!quiet) {
        fprintf(stderr, "illum: tonemap: %s", op_name(tm.desc.op));
        if (tm.desc.auto_exposure) {
            double p = tm.desc.auto_percentile > 0.0f ? tm.desc.auto_percentile : 99.0;
            if (auto_lum > 0.0)
                fprintf(stderr,
                        ", exposure %+.3g EV (%+.3g manual, %+.3g auto: luminance %.4g at the "
                        "%g%% percentile maps to 1)",
                        exposure - log2(auto_lum), exposure, -log2(auto_lum), auto_lum, p);
            else
                fprintf(stderr, ", exposure %+.3g EV (auto: every pixel is black)", exposure);
        } else {
            fprintf(stderr, ", exposure %+.3g EV", exposure);
        }
        if (tm.desc.bloom > 0.0f)
            fprintf(stderr, ", bloom %g", (double)tm.desc.bloom);
        fprintf(stderr, " -> %s\n", out_path);
    }
    return IL_EXIT_OK;
}
