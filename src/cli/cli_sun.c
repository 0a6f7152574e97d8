/* The sun of a CIE sky on the command line (docs/environment.md#skies):
 * --sun ALT,AZ, or --sun-time MOMENT with --latitude and --longitude;
 * --north, --sun-lux.  Shared by render, bake, view and illuminance
 * through cli_env_option. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

/* Days from 1970-01-01 to the proleptic Gregorian date y-m-d (H. Hinnant's
 * days_from_civil: years counted from March, in 400-year eras). */
static long days_from_civil(long y, int m, int d)
{
    y -= m <= 2;
    long era = (y >= 0 ? y : y - 399) / 400;
    long yoe = y - era * 400;
    long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

static bool leap(long y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

/* Reads exactly n digits at *p into *out. */
static bool digits(const char **p, int n, long *out)
{
    long v = 0;
    for (int k = 0; k < n; k++, (*p)++) {
        if (!isdigit((unsigned char)**p))
            return false;
        v = 10 * v + (**p - '0');
    }
    *out = v;
    return true;
}

bool cli_parse_moment(const char *opt, const char *s, double *unix_seconds, int *day_of_year)
{
    const char *p = s;
    long y, mo, d, h, mi, sec = 0, zh = 0, zm = 0;
    double frac = 0.0;
    int sign = 0;
    bool ok = digits(&p, 4, &y) && *p++ == '-' && digits(&p, 2, &mo) && *p++ == '-' && digits(&p, 2, &d) &&
              (*p == 'T' || *p == 't' || *p == ' ') && (p++, digits(&p, 2, &h)) && *p++ == ':' &&
              digits(&p, 2, &mi);
    if (ok && *p == ':') {
        p++;
        ok = digits(&p, 2, &sec);
        if (ok && *p == '.') {
            double scale = 0.1;
            for (p++; isdigit((unsigned char)*p); p++, scale /= 10.0)
                frac += scale * (*p - '0');
        }
    }
    if (ok && (*p == 'Z' || *p == 'z') && p[1] == '\0') {
        sign = 1;
    } else if (ok && (*p == '+' || *p == '-')) {
        sign = *p++ == '-' ? -1 : 1;
        ok = digits(&p, 2, &zh);
        if (ok && *p == ':')
            p++;
        if (ok && *p)
            ok = digits(&p, 2, &zm);
        ok = ok && *p == '\0';
    }
    if (!ok || !sign) {
        cli_error("%s: expected a date, a time and its UTC offset, as 2026-06-21T14:30+02:00 or "
                  "2026-06-21T12:30Z, got '%s'",
                  opt, s);
        return false;
    }
    static const int month_days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (y < 1900 || y > 2100 || mo < 1 || mo > 12 || d < 1 ||
        d > month_days[mo - 1] + (mo == 2 && leap(y)) || h > 23 || mi > 59 || sec > 59 || zh > 14 || zm > 59) {
        cli_error("%s: '%s' is not a valid moment from 1900 to 2100", opt, s);
        return false;
    }
    long days = days_from_civil(y, (int)mo, (int)d);
    *day_of_year = (int)(days - days_from_civil(y, 1, 1) + 1);
    /* Local time minus its offset east of Greenwich is UTC. */
    *unix_seconds = 86400.0 * days + 3600.0 * h + 60.0 * mi + sec + frac - sign * (3600.0 * zh + 60.0 * zm);
    return true;
}

bool cli_sun_option(const char *a, const char *v, cli_env_options *o, int *rc)
{
    bool sun = !strcmp(a, "--sun"), time = !strcmp(a, "--sun-time"), lat = !strcmp(a, "--latitude"),
         lon = !strcmp(a, "--longitude"), north = !strcmp(a, "--north"), lux = !strcmp(a, "--sun-lux");
    if (!sun && !time && !lat && !lon && !north && !lux)
        return false;
    if (!o->first_sun_setting)
        o->first_sun_setting = a;
    bool ok = true;
    if (sun) {
        double aa[2];
        ok = cli_parse_numbers(a, v, 2, "ALTITUDE,AZIMUTH in degrees", aa);
        if (ok && !(aa[0] >= -90.0 && aa[0] <= 90.0)) {
            cli_error("--sun: the altitude %g is not -90 to 90 degrees", aa[0]);
            ok = false;
        }
        o->sky_desc.sun_altitude = aa[0];
        o->sky_desc.sun_azimuth = aa[1];
        o->has_sun = true;
    } else if (time) {
        ok = cli_parse_moment(a, v, &o->sun_seconds, &o->sun_day_of_year);
        o->sun_time = v;
    } else if (lat) {
        ok = cli_parse_double(a, v, -90.0, 90.0, &o->latitude);
        o->has_latitude = true;
    } else if (lon) {
        ok = cli_parse_double(a, v, -180.0, 180.0, &o->longitude);
        o->has_longitude = true;
    } else if (north) {
        ok = cli_parse_double(a, v, -360.0, 360.0, &o->sky_desc.north);
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
    if (!o->has_sun) {
        il_error err = {0};
        if (il_sun_position(o->latitude, o->longitude, o->sun_seconds, &desc->sun_altitude,
                            &desc->sun_azimuth, &err) != IL_OK) {
            cli_error("--sun-time: %s", err.message);
            return cli_exit_for(err.status);
        }
    }
    if (!(desc->sun_altitude > 0.0)) {
        if (o->has_sun)
            cli_error("--sun: the altitude %g is not above the horizon; a CIE sky needs the sun up",
                      desc->sun_altitude);
        else
            cli_error("--sun-time: at %s the sun stands %.2f degrees below the horizon at %g, %g; "
                      "a CIE sky needs it up",
                      o->sun_time, -desc->sun_altitude, o->latitude, o->longitude);
        return IL_EXIT_BAD_INPUT;
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
