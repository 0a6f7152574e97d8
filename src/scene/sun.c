/* The sun for daylight studies: where it stands (il_sun_position) and how
 * much light reaches the ground from it (il_sun_normal_lux).
 *
 * Position: the Astronomical Almanac's low-precision formulas for the
 * sun's coordinates, as published for solar-energy use by Michalsky (1988,
 * "The Astronomical Almanac's algorithm for approximate solar position
 * (1950-2050)", Solar Energy 40(3)), about 0.01 degree; sidereal time after
 * Meeus, Astronomical Algorithms (2nd ed.), eq. 12.4; refraction after
 * Saemundsson (Meeus eq. 16.4). */
#include <ctype.h>
#include <math.h>
#include <stdbool.h>

#include "core/error.h"
#include "illum/illum.h"
#include "scene/sun.h"

#define DEG (3.14159265358979323846 / 180.0)

/* x reduced to [0, 360). */
static double wrap360(double x)
{
    x = fmod(x, 360.0);
    return x < 0.0 ? x + 360.0 : x;
}

il_status il_sun_position(double latitude, double longitude, double unix_seconds,
                          double *altitude, double *azimuth, il_error *err)
{
    if (!altitude || !azimuth)
        return il_fail(err, IL_ERR_INVALID, "sun position: no output");
    if (!(fabs(latitude) <= 90.0))
        return il_fail(err, IL_ERR_INVALID, "sun position: latitude %g is not -90 to 90 degrees", latitude);
    if (!(fabs(longitude) <= 180.0))
        return il_fail(err, IL_ERR_INVALID, "sun position: longitude %g is not -180 to 180 degrees", longitude);
    /* 1900-01-01 and 2101-01-01, 00:00 UTC */
    if (!(unix_seconds >= -2208988800.0 && unix_seconds < 4133980800.0))
        return il_fail(err, IL_ERR_INVALID, "sun position: the moment is outside the years 1900 to 2100");
    /* Days from J2000.0 (2000-01-01 12:00, JD 2451545.0); the Unix epoch is
     * JD 2440587.5.  UT stands in for TT: the ~1 minute between them moves
     * the sun by under 0.001 degree. */
    double n = unix_seconds / 86400.0 + 2440587.5 - 2451545.0;
    double mean_longitude = wrap360(280.460 + 0.9856474 * n);
    double mean_anomaly = wrap360(357.528 + 0.9856003 * n) * DEG;
    double ecliptic = (mean_longitude + 1.915 * sin(mean_anomaly) + 0.020 * sin(2.0 * mean_anomaly)) * DEG;
    double obliquity = (23.439 - 0.0000004 * n) * DEG;
    double right_ascension = atan2(cos(obliquity) * sin(ecliptic), cos(ecliptic));
    double declination = asin(sin(obliquity) * sin(ecliptic));
    double sidereal = wrap360(280.46061837 + 360.98564736629 * n + longitude);
    double hour_angle = sidereal * DEG - right_ascension;
    double phi = latitude * DEG;
    double sin_h = sin(phi) * sin(declination) + cos(phi) * cos(declination) * cos(hour_angle);
    double h = asin(fmax(-1.0, fmin(1.0, sin_h))) / DEG;
    /* Azimuth from north through east: the hour angle grows westwards. */
    double a = atan2(-cos(declination) * sin(hour_angle),
                     sin(declination) * cos(phi) - cos(declination) * cos(hour_angle) * sin(phi));
    /* Refraction lifts the sun by R arcminutes = 1.02 / tan(h + 10.3 / (h +
     * 5.11)) (h in degrees; 1010 hPa, 10 C); below -1 degree it is left out. */
    if (h > -1.0)
        h += 1.02 / tan((h + 10.3 / (h + 5.11)) * DEG) / 60.0;
    *altitude = h;
    *azimuth = wrap360(a / DEG);
    return IL_OK;
}

double il_sun_normal_lux(int cie_type, double sun_altitude, int day_of_year)
{
    if (cie_type < 6 || cie_type > 15 || !(sun_altitude > 0.0))
        return 0.0;
    double extinction = cie_type >= 11 ? 0.21 : 0.80;
    double season = day_of_year >= 1 && day_of_year <= 366
                        ? 1.0 + 0.034 * cos(2.0 * 3.14159265358979323846 * (day_of_year - 2) / 365.0)
                        : 1.0;
    double air_mass = 1.0 / sin(fmin(sun_altitude, 90.0) * DEG);
    return 127500.0 * season * exp(-extinction * air_mass);
}

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

il_status il_parse_moment(const char *s, double *unix_seconds, int *day_of_year, il_error *err)
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
    if (!ok || !sign)
        return il_fail(err, IL_ERR_INVALID,
                       "expected a date, a time and its UTC offset, as 2026-06-21T14:30+02:00 or "
                       "2026-06-21T12:30Z, got '%s'",
                       s);
    static const int month_days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (y < 1900 || y > 2100 || mo < 1 || mo > 12 || d < 1 ||
        d > month_days[mo - 1] + (mo == 2 && leap(y)) || h > 23 || mi > 59 || sec > 59 || zh > 14 || zm > 59)
        return il_fail(err, IL_ERR_INVALID, "'%s' is not a valid moment from 1900 to 2100", s);
    long days = days_from_civil(y, (int)mo, (int)d);
    *day_of_year = (int)(days - days_from_civil(y, 1, 1) + 1);
    /* Local time minus its offset east of Greenwich is UTC. */
    *unix_seconds = 86400.0 * days + 3600.0 * h + 60.0 * mi + sec + frac - sign * (3600.0 * zh + 60.0 * zm);
    return IL_OK;
}

il_status il_sun_place(il_sky_desc *desc, double latitude, double longitude, double unix_seconds,
                       const char *moment, il_error *err)
{
    il_status st = il_sun_position(latitude, longitude, unix_seconds, &desc->sun_altitude,
                                   &desc->sun_azimuth, err);
    if (st != IL_OK)
        return st;
    if (!(desc->sun_altitude > 0.0))
        return il_fail(err, IL_ERR_INVALID,
                       "at %s the sun stands %.2f degrees below the horizon at %g, %g; a CIE sky needs it up",
                       moment, -desc->sun_altitude, latitude, longitude);
    return IL_OK;
}
