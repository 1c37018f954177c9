/* The pilot's loops (pilot_law.h): the plugin's behaviors and libauvpilot.so
 * both run this file, so nothing here may call CHASM. */
#include <math.h>

#include "plugins/lib/pu_angle.h"
#include "plugins/pilot/pilot_law.h"

/* ------------------------------------------------------------------ pitch */

/* The PID works in "bow-up demand" (positive: raise the bow), which is the
 * negative of the stern plane: positive plane pitches the bow down. */
void pilot_pitch_start(pilot_pitch_loop *l, double current_plane)
{
    pu_pid_reset(&l->pid);
    pu_pid_preset_output(&l->pid, -current_plane);
}

double pilot_pitch_step(pilot_pitch_loop *l, const pilot_pitch_gains *g, double pitch_cmd, double pitch, double q,
                        double dt)
{
    const pu_pid_config cfg = {
        .kp = g->kp,
        .ki = g->ki,
        .kd = g->kd,
        .out_min = -g->max_plane,
        .out_max = g->max_plane,
        .rate_max = g->plane_slew,
        .i_limit = g->plane_i_limit,
    };
    /* d(error)/dt = -q for a steady command: damping from the gyro, no kick */
    return -pu_pid_step(&l->pid, &cfg, pitch_cmd - pitch, -q, 0.0, dt);
}

double pilot_pitch_hold(pilot_pitch_loop *l, const pilot_pitch_gains *g, double max_pitch, double setpoint,
                        double pitch, double q, double dt)
{
    return pilot_pitch_step(l, g, pu_clamp_sym(setpoint, max_pitch), pitch, q, dt);
}

/* ------------------------------------------------------------------ depth */

void pilot_depth_start(pilot_depth_loop *l, double pitch0, double plane0)
{
    pu_pid_reset(&l->pid);
    pu_pid_preset_output(&l->pid, pitch0);
    pu_lowpass_reset(&l->rate);
    l->has_last_depth = 0;
    pilot_pitch_start(&l->pitch, plane0);
}

double pilot_depth_step(pilot_depth_loop *l, const pilot_depth_gains *g, double target, double depth, double pitch,
                        double q, double dt)
{
    const pu_pid_config cfg = {
        .kp = g->kp,
        .ki = g->ki,
        .kd = g->kd,
        .out_min = -g->max_pitch,
        .out_max = g->max_pitch,
        .rate_max = g->pitch_slew,
        .i_limit = g->max_pitch,
    };
    double rate = 0.0;
    if (isfinite(depth)) {
        if (l->has_last_depth && dt > 0.0)
            rate = pu_lowpass_step(&l->rate, (depth - l->last_depth) / dt, g->depth_rate_tau, dt);
        else if (l->rate.primed)
            rate = l->rate.y;
        l->last_depth = depth;
        l->has_last_depth = 1;
    }
    target = pu_clamp(target, 0.0, g->max_depth);
    /* too deep (positive error) -> bow up (positive pitch command) */
    double pitch_cmd = pu_pid_step(&l->pid, &cfg, depth - target, rate, 0.0, dt);
    return pilot_pitch_step(&l->pitch, &g->pitch, pitch_cmd, pitch, q, dt);
}

/* ---------------------------------------------------------------- heading */

void pilot_heading_start(pilot_heading_loop *l, double current_rudder)
{
    pu_pid_reset(&l->pid);
    pu_pid_preset_output(&l->pid, current_rudder);
}

double pilot_heading_step(pilot_heading_loop *l, const pilot_heading_gains *g, double setpoint, double heading,
                          double r, double dt)
{
    pu_pid_config cfg = {
        .kp = g->kp,
        .ki = g->ki,
        .kd = g->kd,
        .out_min = -g->max_rudder,
        .out_max = g->max_rudder,
        .rate_max = g->rudder_slew,
        .i_limit = g->i_limit,
        .i_zone = g->i_zone,
    };
    double e = pu_angle_diff(setpoint, heading);
    /* Limit the error the P term sees so kp e never asks for more than
     * max_turn_rate: kp e_lim = kd max_turn_rate. */
    double e_lim = g->kp > 0.0 ? pu_clamp_sym(e, g->kd * g->max_turn_rate / g->kp) : e;
    if (e_lim != e)
        cfg.ki = 0.0; /* outside the linear region: never integrate (see i_zone) */
    return pu_pid_step(&l->pid, &cfg, e_lim, isfinite(r) ? -r : NAN, 0.0, dt);
}

/* ---------------------------------------------------------------- the prop */

void pilot_prop_start(pilot_prop_loop *l, double current_rpm)
{
    pu_pid_reset(&l->pid);
    pu_pid_preset_output(&l->pid, current_rpm);
}

double pilot_speed_step(pilot_prop_loop *l, const pilot_prop_gains *g, double sp, double speed, int through_water,
                        double dt)
{
    pu_pid_config cfg = {
        .kp = g->kp,
        .ki = g->ki,
        .out_min = g->min_rpm,
        .out_max = g->max_rpm,
        .rate_max = g->rpm_slew,
        .i_limit = g->i_limit,
    };
    if (through_water) {
        /* through the water: the calibrated propeller law is the speed through
         * the water; closing the loop on the (over-ground) navigation speed
         * would fight or ride a current. No stored integral either. */
        l->pid.integral = 0.0;
        cfg.kp = cfg.ki = 0.0;
    }
    if (!(sp > 0.0)) {
        /* stop means stop: no PI fighting a drifting vehicle, no stored integral */
        l->pid.integral = 0.0;
        cfg.kp = cfg.ki = 0.0;
        return pu_pid_step(&l->pid, &cfg, 0.0, 0.0, 0.0, dt);
    }
    return pu_pid_step(&l->pid, &cfg, sp - speed, 0.0, g->rpm_per_mps * sp, dt);
}

double pilot_rpm_step(pilot_prop_loop *l, const pilot_prop_gains *g, double rpm, double dt)
{
    const pu_pid_config cfg = {
        .out_min = g->min_rpm,
        .out_max = g->max_rpm,
        .rate_max = g->rpm_slew,
    };
    /* a pure feed-forward PID: limits and slew only */
    return pu_pid_step(&l->pid, &cfg, 0.0, 0.0, rpm, dt);
}
