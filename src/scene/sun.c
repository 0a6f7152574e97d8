/* The sun for daylight studies: where it stands (il_sun_position) and how
 * much light reaches the ground from it (il_sun_normal_lux).
 *
 * Position: the Astronomical Almanac's low-precision formulas for the
 * sun's coordinates, as published for solar-energy use by Michalsky (1988,
 * "The Astronomical Almanac's algorithm for approximate solar position
 * (1950-2050)", Solar Energy 40(3)), about 0.01 degree; sidereal time after
 * Meeus, Astronomical Algorithms (2nd ed.), eq. 12.4; refraction after
 * Saemundsson (Meeus eq. 16.4). */
#include <math.h>

#include "core/error.h"
#include "illum/illum.h"

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
