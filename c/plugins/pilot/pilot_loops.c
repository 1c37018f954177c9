/* The pitch and depth loops shared by the vertical behaviors (pilot.h). */
#include <math.h>

#include "plugins/pilot/pilot.h"

void pilot_pitch_config(const chasm_ctx *c, int base, pu_pid_config *out)
{
    double max_plane = chasm_param_double(c, base + PL_MAX_PLANE);
    *out = (pu_pid_config){
        .kp = chasm_param_double(c, base + PL_KP),
        .ki = chasm_param_double(c, base + PL_KI),
        .kd = chasm_param_double(c, base + PL_KD),
        .out_min = -max_plane,
        .out_max = max_plane,
        .rate_max = chasm_param_double(c, base + PL_PLANE_SLEW),
        .i_limit = chasm_param_double(c, base + PL_I_LIMIT),
    };
}

/* The PID works in "bow-up demand" (positive: raise the bow), which is the
 * negative of the stern plane: positive plane pitches the bow down. */
void pilot_pitch_start(pilot_pitch_loop *l, double current_plane)
{
    pu_pid_reset(&l->pid);
    pu_pid_preset_output(&l->pid, -current_plane);
}

double pilot_pitch_step(pilot_pitch_loop *l, const pu_pid_config *cfg, double pitch_cmd, double pitch, double q,
                        double dt)
{
    /* d(error)/dt = -q for a steady command: damping from the gyro, no kick */
    return -pu_pid_step(&l->pid, cfg, pitch_cmd - pitch, -q, 0.0, dt);
}

void pilot_depth_config_read(const chasm_ctx *c, int depth_base, int pitch_base, pilot_depth_config *out)
{
    double max_pitch = chasm_param_double(c, depth_base + DL_MAX_PITCH);
    out->depth = (pu_pid_config){
        .kp = chasm_param_double(c, depth_base + DL_KP),
        .ki = chasm_param_double(c, depth_base + DL_KI),
        .kd = chasm_param_double(c, depth_base + DL_KD),
        .out_min = -max_pitch,
        .out_max = max_pitch,
        .rate_max = chasm_param_double(c, depth_base + DL_PITCH_SLEW),
        .i_limit = max_pitch,
    };
    out->max_depth = chasm_param_double(c, depth_base + DL_MAX_DEPTH);
    out->rate_tau = chasm_param_double(c, depth_base + DL_RATE_TAU);
    pilot_pitch_config(c, pitch_base, &out->pitch);
}

void pilot_depth_start(pilot_depth_loop *l, double pitch0, double plane0)
{
    pu_pid_reset(&l->pid);
    pu_pid_preset_output(&l->pid, pitch0);
    pu_lowpass_reset(&l->rate);
    l->has_last_depth = 0;
    pilot_pitch_start(&l->pitch, plane0);
}

double pilot_depth_step(pilot_depth_loop *l, const pilot_depth_config *cfg, double target, double depth,
                        double pitch, double q, double dt)
{
    double rate = 0.0;
    if (isfinite(depth)) {
        if (l->has_last_depth && dt > 0.0)
            rate = pu_lowpass_step(&l->rate, (depth - l->last_depth) / dt, cfg->rate_tau, dt);
        else if (l->rate.primed)
            rate = l->rate.y;
        l->last_depth = depth;
        l->has_last_depth = 1;
    }
    target = pu_clamp(target, 0.0, cfg->max_depth);
    /* too deep (positive error) -> bow up (positive pitch command) */
    double pitch_cmd = pu_pid_step(&l->pid, &cfg->depth, depth - target, rate, 0.0, dt);
    return pilot_pitch_step(&l->pitch, &cfg->pitch, pitch_cmd, pitch, q, dt);
}
