#include "methods/sensor_check.h"

#include "core/error.h"
#include "core/vec.h"

il_status il_sensors_check(const char *who, const il_sensor *sensors, size_t count, il_error *err)
{
    for (size_t i = 0; i < count; i++) {
        il_vec3 p = sensors[i].position, n = sensors[i].normal;
        if (!v3_is_finite(p) || !v3_is_finite(n))
            return il_fail(err, IL_ERR_INVALID, "%s: sensor %zu has a NaN or infinite coordinate", who, i);
        if (!(v3_length(n) > 0.0f))
            return il_fail(err, IL_ERR_INVALID, "%s: sensor %zu has a zero normal", who, i);
    }
    return IL_OK;
}
