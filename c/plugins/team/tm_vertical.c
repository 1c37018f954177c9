#include <math.h>

#include "tm_behaviors.h"

void tm_vertical(chasm_ctx *c, int depth, int altitude, int out_mode, int out_depth, int out_altitude, double offset)
{
    double alt = chasm_param_double(c, altitude);
    if (alt != TM_ABSENT) {
        chasm_write_int(c, out_mode, 1);
        chasm_write_double(c, out_altitude, fmax(0.5, alt - offset));
    } else {
        chasm_write_int(c, out_mode, 0);
        chasm_write_double(c, out_depth, chasm_param_double(c, depth) + offset);
    }
}
