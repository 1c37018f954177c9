/* libauvpilot.so: the pilot plugin's control law for callers that fly a
 * vehicle in-process, with no CHASM manager, no LCM and no clock: the
 * simulator's validation report (python/sim/pilot.py binds it with ctypes).
 *
 * The loops are c/plugins/pilot/pilot_loops.c, the very file the pilot
 * plugin runs, compiled into this library: there is no second copy of the
 * law. What the library adds is the plan's wiring of them, one instance of
 * each loop as missions/pilot/pilot.chasm runs them in its `fly` state:
 * heading_control on the rudder, depth_control or pitch_control on the
 * stern plane, speed_control or rpm_control on the prop.
 *
 * Gains are set by name, each named as the `param` of pilot.chasm that the
 * plan passes to the behaviors (AUV_PILOT_GAINS), in SI units; the binding
 * reads them from the plan, so this library holds no default either. The
 * caller allocates auv_pilot_size() bytes (aligned for a double); nothing
 * here allocates.
 *
 * Starting: each family of loops starts from the actuator's current command
 * (bumpless), as a behavior's start() does when its state is entered.
 * depth and pitch share the stern plane's state: start the vertical loops
 * again when changing from one to the other, as the plan does (a new leaf).
 */
#ifndef AUV_PILOT_H
#define AUV_PILOT_H

#include <stddef.h>

/* Plan parameter name, then the field of the gains it fills. */
#define AUV_PILOT_GAINS(X)                                                                                     \
    X(heading_kp, heading.kp) X(heading_ki, heading.ki) X(heading_kd, heading.kd)                              \
    X(max_turn_rate, heading.max_turn_rate) X(max_rudder, heading.max_rudder)                                  \
    X(rudder_slew, heading.rudder_slew) X(heading_i_limit, heading.i_limit) X(heading_i_zone, heading.i_zone)  \
    X(depth_kp, depth.kp) X(depth_ki, depth.ki) X(depth_kd, depth.kd) X(max_pitch, depth.max_pitch)            \
    X(pitch_slew, depth.pitch_slew) X(max_depth, depth.max_depth) X(depth_rate_tau, depth.depth_rate_tau)      \
    X(pitch_kp, depth.pitch.kp) X(pitch_ki, depth.pitch.ki) X(pitch_kd, depth.pitch.kd)                        \
    X(max_plane, depth.pitch.max_plane) X(plane_slew, depth.pitch.plane_slew)                                  \
    X(plane_i_limit, depth.pitch.plane_i_limit)                                                                \
    X(rpm_per_mps, prop.rpm_per_mps) X(speed_kp, prop.kp) X(speed_ki, prop.ki) X(speed_i_limit, prop.i_limit)  \
    X(min_rpm, prop.min_rpm) X(max_rpm, prop.max_rpm) X(rpm_slew, prop.rpm_slew)

typedef struct auv_pilot auv_pilot;

size_t auv_pilot_size(void);
/* Every gain 0, every loop reset. */
void auv_pilot_init(auv_pilot *p);

/* The gains, as AUV_PILOT_GAINS lists them: count, and the i-th's name
 * (NULL past the end). */
size_t auv_pilot_gain_count(void);
const char *auv_pilot_gain_name(size_t i);
/* 0, or -1 for a name that is not a gain. */
int auv_pilot_set_gain(auv_pilot *p, const char *name, double value);
double auv_pilot_gain(const auv_pilot *p, const char *name); /* NaN for an unknown name */

/* Take over the actuators from their current commands. */
void auv_pilot_start_heading(auv_pilot *p, double rudder);
void auv_pilot_start_vertical(auv_pilot *p, double pitch, double plane);
void auv_pilot_start_prop(auv_pilot *p, double rpm);

/* One control cycle of dt seconds each (angles rad, rates rad/s, depth m
 * positive down, pitch positive bow up, speeds m/s); the actuator command. */
double auv_pilot_rudder(auv_pilot *p, double heading_cmd, double heading, double r, double dt);
double auv_pilot_plane_for_depth(auv_pilot *p, double depth_cmd, double depth, double pitch, double q, double dt);
/* pitch_control, its setpoint clamped to +-max_pitch as the plan passes it. */
double auv_pilot_plane_for_pitch(auv_pilot *p, double pitch_cmd, double pitch, double q, double dt);
/* speed_control; through_water: setpoint_t.SPEED_THROUGH_WATER (the rpm law alone). */
double auv_pilot_prop_for_speed(auv_pilot *p, double speed_cmd, double u, int through_water, double dt);
/* rpm_control. */
double auv_pilot_prop_for_rpm(auv_pilot *p, double rpm_cmd, double dt);

#endif
