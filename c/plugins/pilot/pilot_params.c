/* The vertical loops' parameter blocks read into pilot_law.h's gains. Kept
 * apart from pilot_loops.c, which libauvpilot.so also builds without CHASM. */
#include "plugins/pilot/pilot.h"

void pilot_pitch_gains_read(const chasm_ctx *c, int base, pilot_pitch_gains *out)
{
    *out = (pilot_pitch_gains){
        .kp = chasm_param_double(c, base + PL_KP),
        .ki = chasm_param_double(c, base + PL_KI),
        .kd = chasm_param_double(c, base + PL_KD),
        .max_plane = chasm_param_double(c, base + PL_MAX_PLANE),
        .plane_slew = chasm_param_double(c, base + PL_PLANE_SLEW),
        .plane_i_limit = chasm_param_double(c, base + PL_I_LIMIT),
    };
}

void pilot_depth_gains_read(const chasm_ctx *c, int depth_base, int pitch_base, pilot_depth_gains *out)
{
    *out = (pilot_depth_gains){
        .kp = chasm_param_double(c, depth_base + DL_KP),
        .ki = chasm_param_double(c, depth_base + DL_KI),
        .kd = chasm_param_double(c, depth_base + DL_KD),
        .max_pitch = chasm_param_double(c, depth_base + DL_MAX_PITCH),
        .pitch_slew = chasm_param_double(c, depth_base + DL_PITCH_SLEW),
        .max_depth = chasm_param_double(c, depth_base + DL_MAX_DEPTH),
        .depth_rate_tau = chasm_param_double(c, depth_base + DL_RATE_TAU),
    };
    pilot_pitch_gains_read(c, pitch_base, &out->pitch);
}
