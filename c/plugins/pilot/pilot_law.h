/* The pilot's control law with nothing of CHASM in it: the loops, their
 * gains as plain numbers, and the mapping of those gains onto pu_pid.
 *
 * Two callers compile this same source (pilot_loops.c): the pilot plugin's
 * behaviors (pilot.h), which read the gains from their plan parameters, and
 * libauvpilot.so (c/pilotlib), through which the simulator's validation
 * flies the vehicle in-process. So the law exists once; only where the
 * numbers come from differs, and both take them from missions/pilot/pilot.chasm.
 *
 * Signs are those of auv.actuators_t (pilot.h). Every gain is SI, named as
 * the behavior parameter it comes from. A loop's state is zeroed by its
 * start function; the gains are read at every step, as the behaviors read
 * their parameters at every cycle.
 */
#ifndef PILOT_LAW_H
#define PILOT_LAW_H

#include "plugins/lib/pu_limit.h"
#include "plugins/lib/pu_pid.h"

#pragma GCC visibility push(hidden)

/* ---- pitch loop: pitch command -> stern plane (PID with pitch-rate damping) */
typedef struct {
    double kp, ki, kd, max_plane, plane_slew, plane_i_limit;
} pilot_pitch_gains;

typedef struct {
    pu_pid pid;
} pilot_pitch_loop;

/* Starts the loop so its first command continues from the current plane. */
void pilot_pitch_start(pilot_pitch_loop *l, double current_plane);
/* Stern plane for pitch_cmd given pitch and pitch rate q. */
double pilot_pitch_step(pilot_pitch_loop *l, const pilot_pitch_gains *g, double pitch_cmd, double pitch, double q,
                        double dt);
/* pitch_control: the same for a setpoint, clamped first to +-max_pitch. */
double pilot_pitch_hold(pilot_pitch_loop *l, const pilot_pitch_gains *g, double max_pitch, double setpoint,
                        double pitch, double q, double dt);

/* ---- depth loop: depth target -> pitch command (then the pitch loop) */
typedef struct {
    double kp, ki, kd, max_pitch, pitch_slew, max_depth, depth_rate_tau;
    pilot_pitch_gains pitch;
} pilot_depth_gains;

typedef struct {
    pu_pid pid;
    pu_lowpass rate; /* depth rate, differenced and filtered */
    double last_depth;
    int has_last_depth;
    pilot_pitch_loop pitch;
} pilot_depth_loop;

/* pitch0/plane0: the vehicle's pitch and the current plane command, so the
 * loops take over without a jump. */
void pilot_depth_start(pilot_depth_loop *l, double pitch0, double plane0);
/* Stern plane that brings depth to target. */
double pilot_depth_step(pilot_depth_loop *l, const pilot_depth_gains *g, double target, double depth, double pitch,
                        double q, double dt);

/* ---- heading loop: heading -> rudder (pilot_heading.c says why this shape) */
typedef struct {
    double kp, ki, kd, max_turn_rate, max_rudder, rudder_slew, i_limit, i_zone;
} pilot_heading_gains;

typedef struct {
    pu_pid pid;
} pilot_heading_loop;

void pilot_heading_start(pilot_heading_loop *l, double current_rudder);
/* Rudder that brings heading to setpoint (headings in rad, r the yaw rate). */
double pilot_heading_step(pilot_heading_loop *l, const pilot_heading_gains *g, double setpoint, double heading,
                          double r, double dt);

/* ---- propeller: speed (feed-forward + PI) or rpm (open loop) -> prop rpm */
typedef struct {
    double rpm_per_mps, kp, ki, i_limit, min_rpm, max_rpm, rpm_slew;
} pilot_prop_gains;

typedef struct {
    pu_pid pid;
} pilot_prop_loop;

void pilot_prop_start(pilot_prop_loop *l, double current_rpm);
/* Prop rpm for speed setpoint sp [m/s]; through_water: the rpm law alone,
 * no loop on the (over-ground) measured speed (setpoint_t). */
double pilot_speed_step(pilot_prop_loop *l, const pilot_prop_gains *g, double sp, double speed, int through_water,
                        double dt);
/* Prop rpm for an rpm setpoint: limits and slew only (rpm_per_mps, kp, ki unused). */
double pilot_rpm_step(pilot_prop_loop *l, const pilot_prop_gains *g, double rpm, double dt);

#pragma GCC visibility pop
#endif
