/* The sun of a CIE sky on the command line (docs/environment.md#skies):
 * --sun ALT,AZ, or --sun-time MOMENT with --latitude and --longitude;
 * --north, --sun-lux, --sun-diameter.  Shared by render, bake, view and
 * illuminance through cli_env_option. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "scene/sun.h"

bool cli_sun_option(int argc, char **argv, int *i, cli_env_options *o, int *rc)
{
    const char *a = argv[*i];
    bool sun = !strcmp(a, "--sun"), time = !strcmp(a, "--sun-time"), lat = !strcmp(a, "--latitude"),
         lon = !strcmp(a, "--longitude"), north = !strcmp(a, "--north"), lux = !strcmp(a, "--sun-lux"),
         diameter = !strcmp(a, "--sun-diameter");
    if (!sun && !time && !lat && !lon && !north && !lux && !diameter)
        return false;
    const char *v = cli_value(argc, argv, i);
    if (!v) {
        *rc = IL_EXIT_USAGE;
        return true;
    }
    if (!o->first_sun_setting)
        o->first_sun_setting = a;
    bool ok = true;
    if (sun) {
        double aa[2] = {0.0, 0.0};
        ok = cli_parse_numbers(a, v, 2, "ALTITUDE,AZIMUTH in degrees", aa);
        if (ok && !(aa[0] >= -90.0 && aa[0] <= 90.0)) {
            cli_error("--sun: the altitude %g is not -90 to 90 degrees", aa[0]);
            ok = false;
        }
        o->sky_desc.sun_altitude = aa[0];
        o->sky_desc.sun_azimuth = aa[1];
        o->has_sun = true;
    } else if (time) {
        il_error err = {0};
        ok = il_parse_moment(v, &o->sun_seconds, &o->sun_day_of_year, &err) == IL_OK;
        if (!ok)
            cli_error("--sun-time: %s", err.message);
        o->sun_time = v;
    } else if (lat) {
        ok = cli_parse_double(a, v, -90.0, 90.0, &o->latitude);
        o->has_latitude = true;
    } else if (lon) {
        ok = cli_parse_double(a, v, -180.0, 180.0, &o->longitude);
        o->has_longitude = true;
    } else if (north) {
        ok = cli_parse_double(a, v, -360.0, 360.0, &o->sky_desc.north);
    } else if (diameter) {
        /* 0 is a point here (the library's 0 is the sun's own size). */
        double d = 0.0;
        ok = cli_parse_double(a, v, 0.0, 90.0, &d);
        o->sky_desc.sun_diameter = d > 0.0 ? d : -1.0;
    } else {
        ok = cli_parse_double(a, v, 0.0, 1e7, &o->sun_lux);
        o->has_sun_lux = true;
    }
    *rc = ok ? IL_EXIT_OK : IL_EXIT_BAD_INPUT;
    return true;
}

int cli_sun_check(const char *command, const cli_env_options *o)
{
    bool cie = o->sky && o->sky_desc.cie_type > 0;
    if (o->first_sun_setting && !cie) {
        cli_error("%s: %s needs a CIE sky: --sky clear or --sky cie:1 to cie:15", command, o->first_sun_setting);
        return IL_EXIT_USAGE;
    }
    if (!cie)
        return IL_EXIT_OK;
    if (o->has_sun && (o->sun_time || o->has_latitude || o->has_longitude)) {
        cli_error("%s: give the sun either as --sun ALT,AZ or by --sun-time with --latitude and --longitude",
                  command);
        return IL_EXIT_USAGE;
    }
    if (!o->has_sun && !(o->sun_time && o->has_latitude && o->has_longitude)) {
        cli_error("%s: a CIE sky needs the sun: --sun ALT,AZ, or --sun-time 2026-06-21T14:30+02:00 "
                  "--latitude DEG --longitude DEG",
                  command);
        return IL_EXIT_USAGE;
    }
    return IL_EXIT_OK;
}

int cli_sun_resolve(const cli_env_options *o, il_sky_desc *desc, bool quiet)
{
    if (desc->cie_type == 0)
        return IL_EXIT_OK;
    if (o->has_sun && !(desc->sun_altitude > 0.0)) {
        cli_error("--sun: the altitude %g is not above the horizon; a CIE sky needs the sun up",
                  desc->sun_altitude);
        return IL_EXIT_BAD_INPUT;
    }
    il_error err = {0};
    if (!o->has_sun && il_sun_place(desc, o->latitude, o->longitude, o->sun_seconds, o->sun_time, &err) != IL_OK) {
        cli_error("--sun-time: %s", err.message);
        return cli_exit_for(err.status);
    }
    desc->sun_normal_lux = o->has_sun_lux ? o->sun_lux
                                          : il_sun_normal_lux(desc->cie_type, desc->sun_altitude,
                                                              o->has_sun ? 0 : o->sun_day_of_year);
    double azimuth = fmod(desc->sun_azimuth, 360.0);
    if (!quiet)
        fprintf(stderr,
                "illum: CIE sky type %d, sun at %.2f degrees altitude, %.2f azimuth; "
                "sky %g lx horizontal, sun %.0f lx normal\n",
                desc->cie_type, desc->sun_altitude, azimuth < 0.0 ? azimuth + 360.0 : azimuth,
                desc->horizontal_lux > 0.0 ? desc->horizontal_lux : 10000.0, desc->sun_normal_lux);
    return IL_EXIT_OK;
}
