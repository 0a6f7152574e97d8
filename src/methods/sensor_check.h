/* The sensors' own check, shared by il_measure_illuminance and
 * il_sun_hours (il_sensor in illum.h). */
#ifndef IL_METHODS_SENSOR_CHECK_H
#define IL_METHODS_SENSOR_CHECK_H

#include <stddef.h>

#include "illum/illum.h"

/* IL_ERR_INVALID, naming `who` and the first bad sensor, when a position or
 * normal is not finite or a normal is zero. */
il_status il_sensors_check(const char *who, const il_sensor *sensors, size_t count, il_error *err);

#endif
