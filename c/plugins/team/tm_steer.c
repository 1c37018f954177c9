/* The setpoints of a steering team behavior (team_survey, ri_reacquire):
 * heading, speed in m/s, and depth or altitude with keep_clear's offset. */
#include <math.h>

#include "tm_behaviors.h"

void tm_steer(chasm_ctx *c, double heading, int speed, int depth, int altitude, int out, double offset)
{
    chasm_write_double(c, out + TM_OUT_HEADING, heading);
    chasm_write_double(c, out + TM_OUT_SPEED, chasm_param_double(c, speed));
    chasm_write_int(c, out + TM_OUT_SPEED_MODE, 0);
    if (chasm_param_given(c, altitude)) {
        chasm_write_int(c, out + TM_OUT_VERTICAL_MODE, 1);
        chasm_write_double(c, out + TM_OUT_ALTITUDE, fmax(0.5, chasm_param_double(c, altitude) - offset));
    } else {
        chasm_write_int(c, out + TM_OUT_VERTICAL_MODE, 0);
        chasm_write_double(c, out + TM_OUT_DEPTH, chasm_param_double(c, depth) + offset);
    }
}
