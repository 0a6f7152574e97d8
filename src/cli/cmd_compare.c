/* `illum compare A B`: the error metrics every validation test and benchmark uses. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

static const char *help =
    "usage: illum compare A B [--diff DIFF.{png,exr,...}] [--max-rmse X] [--max-rel-mse X] [--json]\n"
    "\n"
    "Compares image A against the reference B (EXR, HDR, PFM, PNG, JPEG; same size)\n"
    "and prints: RMSE over all channels, relative MSE (mean of (a-b)^2/(b^2+0.01)),\n"
    "the mean Rec.709 luminance of each, and the largest absolute channel error.\n"
    "  --diff FILE      write |A-B| per pixel to FILE\n"
    "  --max-rmse X     exit with status 4 when the RMSE exceeds X\n"
    "  --max-rel-mse X  exit with status 4 when the relative MSE exceeds X\n"
    "  --json           print the figures as one JSON object\n";

int cmd_compare(int argc, char **argv)
{
    const char *a_path = NULL, *b_path = NULL, *diff_path = NULL;
    double max_rmse = -1.0, max_rel = -1.0;
    bool json = false;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
            fputs(help, stdout);
            return IL_EXIT_OK;
        } else if (!strcmp(arg, "--diff")) {
            if (!(diff_path = cli_value(argc, argv, &i)))
                return IL_EXIT_USAGE;
        } else if (!strcmp(arg, "--max-rmse") || !strcmp(arg, "--max-rel-mse")) {
            const char *v = cli_value(argc, argv, &i);
            if (!v)
                return IL_EXIT_USAGE;
            if (!cli_parse_double(arg, v, 0.0, 1e30, !strcmp(arg, "--max-rmse") ? &max_rmse : &max_rel))
                return IL_EXIT_BAD_INPUT;
        } else if (!strcmp(arg, "--json")) {
            json = true;
        } else if (arg[0] == '-' && arg[1] != '\0') {
            cli_error("compare: unknown option '%s' (see 'illum compare --help')", arg);
            return IL_EXIT_USAGE;
        } else if (!a_path) {
            a_path = arg;
        } else if (!b_path) {
            b_path = arg;
        } else {
            cli_error("compare: two images only ('%s' is extra)", arg);
            return IL_EXIT_USAGE;
        }
    }
    if (!a_path || !b_path) {
        cli_error("compare: needs two images A and B (see 'illum compare --help')");
        return IL_EXIT_USAGE;
    }
    int rc = cli_check_outputs(&diff_path, 1);
    if (rc != IL_EXIT_OK)
        return rc;
    il_error err = {0};
    il_image a = {0}, b = {0}, diff = {0};
    il_compare_result r;
    il_status st = il_image_read(a_path, &a, &err);
    if (st == IL_OK)
        st = il_image_read(b_path, &b, &err);
    if (st == IL_OK)
        st = il_image_compare(&a, &b, &r, diff_path ? &diff : NULL, &err);
    if (st == IL_OK && diff_path)
        st = il_image_write(&diff, diff_path, NULL, &err);
    il_image_free(&a);
    il_image_free(&b);
    il_image_free(&diff);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(st);
    }
    if (json) {
        /* JSON has no NaN or infinity: such a figure is null. */
        const char *keys[] = {"rmse", "rel_mse", "mean_luminance_a", "mean_luminance_b", "max_abs_error"};
        const double vals[] = {r.rmse, r.rel_mse, r.mean_lum_a, r.mean_lum_b, r.max_abs_error};
        for (int k = 0; k < 5; k++) {
            printf("%s\"%s\": ", k ? ", " : "{", keys[k]);
            if (isfinite(vals[k]))
                printf("%.9g", vals[k]);
            else
                fputs("null", stdout);
        }
        puts("}");
    } else
        printf("rmse            %.6g\nrel_mse         %.6g\nmean_luminance  %.6g  %.6g\n"
               "max_abs_error   %.6g\n",
               r.rmse, r.rel_mse, r.mean_lum_a, r.mean_lum_b, r.max_abs_error);
    if ((max_rmse >= 0.0 && !(r.rmse <= max_rmse)) || (max_rel >= 0.0 && !(r.rel_mse <= max_rel))) {
        cli_error("compare: %s and %s differ more than allowed", a_path, b_path);
        return IL_EXIT_DIFFERENT;
    }
    return IL_EXIT_OK;
}
