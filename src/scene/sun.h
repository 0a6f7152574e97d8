/* The sun for daylight studies (sun.c; il_sun_position and
 * il_sun_normal_lux in illum.h): what the command line and the JSON loader
 * share to place it. */
#ifndef IL_SCENE_SUN_H
#define IL_SCENE_SUN_H

#include "illum/illum.h"

/* Parses an ISO 8601 moment with its UTC offset (2026-06-21T14:30+02:00,
 * 2026-06-21T12:30Z; seconds and their fraction optional; a space may stand
 * for the T): seconds since 1970-01-01T00:00Z and the local date's day of
 * the year (1-366).  Years 1900 to 2100. */
il_status il_parse_moment(const char *s, double *unix_seconds, int *day_of_year, il_error *err);

/* Puts desc's sun where it stands at that moment seen from that place
 * (il_sun_position); a sun not above the horizon is an error naming
 * `moment` (the moment as the user wrote it). */
il_status il_sun_place(il_sky_desc *desc, double latitude, double longitude, double unix_seconds,
                       const char *moment, il_error *err);

#endif
