/* The pilot plugin: PID behaviors that turn navigator setpoints into fin and
 * propeller commands (docs/behaviors.md, "Pilot").
 *
 * Sign conventions are those of auv.actuators_t: positive rudder turns the
 * bow to starboard; positive stern plane pitches the bow down. Pitch is
 * positive bow up, depth positive down, headings [0, 2pi) clockwise from
 * north. All values are SI (the plan loader converts).
 *
 * The control law itself is pilot_law.h (pilot_loops.c), free of CHASM so
 * that libauvpilot.so (c/pilotlib) runs the same code; this header adds the
 * behaviors and the reading of their parameters.
 *
 * The vertical behaviors share two loops, whose parameters sit in each
 * schema as one contiguous block (the *_PARAMS(base) macros below, entries
 * indexed from slot base) at an offset the behavior passes in:
 *   depth loop:  depth error -> pitch command (PID, limited, slew-limited)
 *   pitch loop:  pitch error -> stern plane (PID with pitch-rate damping)
 */
#ifndef PILOT_H
#define PILOT_H

#include "chasm/chasm_plugin.h"
#include "plugins/pilot/pilot_law.h"

/* Everything the plugin's files share stays inside the plugin: only the
 * descriptor (CHASM_PLUGIN_EXPORT) is visible to the loader. */
#pragma GCC visibility push(hidden)

#define PILOT_DEG (3.14159265358979323846 / 180.0)

/* ---- pitch loop: pitch command -> stern plane */
enum { PL_KP, PL_KI, PL_KD, PL_MAX_PLANE, PL_PLANE_SLEW, PL_I_LIMIT, PL_COUNT };
/* Gains and limits have no defaults: the plan gives every one (docs/behaviors.md). */
#define PILOT_PITCH_LOOP_PARAMS(base)                                                                          \
    [(base) + PL_KP] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("pitch_kp", "", 0, 50,                               \
                                                         "stern plane per pitch error [rad/rad]"),            \
    [(base) + PL_KI] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("pitch_ki", "", 0, 20,                               \
                                                         "stern plane per integrated pitch error [rad/(rad s)]"), \
    [(base) + PL_KD] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("pitch_kd", "", 0, 50,                               \
                                                         "stern plane per pitch rate: the damping [rad/(rad/s)]"), \
    [(base) + PL_MAX_PLANE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_plane", "rad", 0.5 * PILOT_DEG,          \
                                                                60 * PILOT_DEG, "stern plane limit"),         \
    [(base) + PL_PLANE_SLEW] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("plane_slew", "rad/s", 0, 1000 * PILOT_DEG,  \
                                                                 "stern plane slew limit (0: none)"),         \
    [(base) + PL_I_LIMIT] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE(                                                 \
        "plane_i_limit", "rad", 0, 60 * PILOT_DEG, "largest stern plane the pitch integrator may hold (trim)")

/* Reads the pitch-loop block starting at slot base. */
void pilot_pitch_gains_read(const chasm_ctx *c, int base, pilot_pitch_gains *out);

/* ---- depth loop: depth target -> pitch command (then the pitch loop) */
enum { DL_KP, DL_KI, DL_KD, DL_MAX_PITCH, DL_PITCH_SLEW, DL_MAX_DEPTH, DL_RATE_TAU, DL_COUNT };
#define PILOT_DEPTH_LOOP_PARAMS(base)                                                                          \
    [(base) + DL_KP] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("kp", "", 0, 10, "pitch per metre of depth error [rad/m]"), \
    [(base) + DL_KI] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("ki", "", 0, 5,                                      \
                                                         "pitch per integrated depth error [rad/(m s)]"),     \
    [(base) + DL_KD] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("kd", "", 0, 20, "pitch per depth rate [rad/(m/s)]"), \
    [(base) + DL_MAX_PITCH] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_pitch", "rad", 0.5 * PILOT_DEG,          \
                                                                60 * PILOT_DEG, "pitch command limit"),       \
    [(base) + DL_PITCH_SLEW] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("pitch_slew", "rad/s", 0, 1000 * PILOT_DEG,  \
                                                                 "pitch command slew limit (0: none)"),       \
    [(base) + DL_MAX_DEPTH] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_depth", "m", 0, 11000,                   \
                                                                "depth targets are clamped to [0, max_depth]"), \
    [(base) + DL_RATE_TAU] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE(                                                \
        "depth_rate_tau", "s", 0, 60, "low-pass time constant of the depth rate used by kd")

/* Reads the depth-loop block at depth_base and the pitch-loop block at pitch_base. */
void pilot_depth_gains_read(const chasm_ctx *c, int depth_base, int pitch_base, pilot_depth_gains *out);

/* ---- behaviors: slots, per-instance state and entry points of each,
 * registered by pilot_plugin.c (one table: chasm_plugin.h, "Registration"). */
#define PILOT_DECLARE(id, nparams)                                    \
    extern const chasm_param_spec pilot_##id##_params[nparams];      \
    int pilot_##id##_start(chasm_ctx *c, void *state);               \
    chasm_status_code pilot_##id##_step(chasm_ctx *c, void *state)

/* heading_control (pilot_heading.c) */
enum { H_HEADING, H_YAW_RATE, H_SETPOINT, H_RUDDER, H_KP, H_KI, H_KD, H_MAX_TURN_RATE, H_MAX_RUDDER, H_RUDDER_SLEW,
       H_I_LIMIT, H_I_ZONE, H_NPARAMS };
typedef struct {
    pilot_heading_loop loop;
} pilot_heading_state;

PILOT_DECLARE(heading_control, H_NPARAMS);

/* speed_control, rpm_control (pilot_speed.c) */
enum { S_SPEED, S_SETPOINT, S_REFERENCE, S_PROP, S_FF, S_KP, S_KI, S_I_LIMIT, S_MIN_RPM, S_MAX_RPM, S_RPM_SLEW,
       S_NPARAMS };
enum { R_SETPOINT, R_PROP, R_MIN_RPM, R_MAX_RPM, R_RPM_SLEW, R_NPARAMS };

typedef struct {
    pilot_prop_loop loop;
} pilot_prop_state;

PILOT_DECLARE(speed_control, S_NPARAMS);
PILOT_DECLARE(rpm_control, R_NPARAMS);

/* depth_control, altitude_control, pitch_control (pilot_vertical.c); the
 * loops' blocks (PILOT_*_LOOP_PARAMS above) start at the *_LOOP slots. */
enum { D_DEPTH, D_PITCH, D_Q, D_SETPOINT, D_PLANE, D_LOOP, D_PITCH_LOOP = D_LOOP + DL_COUNT,
       D_NPARAMS = D_PITCH_LOOP + PL_COUNT };
enum { A_DEPTH, A_ALTITUDE, A_PITCH, A_Q, A_SETPOINT, A_PLANE, A_TAU, A_SEARCH, A_LOOP,
       A_PITCH_LOOP = A_LOOP + DL_COUNT, A_NPARAMS = A_PITCH_LOOP + PL_COUNT };
enum { P_PITCH, P_Q, P_SETPOINT, P_PLANE, P_MAX_PITCH, P_LOOP, P_NPARAMS = P_LOOP + PL_COUNT };

typedef struct {
    pilot_depth_loop loop;
} pilot_depth_state;
typedef struct {
    pilot_depth_loop loop;
    pu_lowpass target;
} pilot_altitude_state;
typedef struct {
    pilot_pitch_loop loop;
} pilot_pitch_state;

PILOT_DECLARE(depth_control, D_NPARAMS);
PILOT_DECLARE(altitude_control, A_NPARAMS);
PILOT_DECLARE(pitch_control, P_NPARAMS);

/* setpoint_watch (pilot_watch.c): no start() */
enum { W_UTIME, W_HEADING, W_DEPTH, W_ALTITUDE, W_PITCH, W_SPEED, W_RPM, W_VMODE, W_SMODE, W_REF,
       W_COUNT, W_IGNORING, W_REASON, W_LAST, W_STATE, W_REF_OUT, W_TIMEOUT, W_FLYING, W_NPARAMS };

typedef struct {
    double last[W_SMODE + 2];  /* utime and values of the last setpoint seen */
    int seen;
} pilot_watch_state;

extern const chasm_param_spec pilot_setpoint_watch_params[W_NPARAMS];
chasm_status_code pilot_setpoint_watch_step(chasm_ctx *c, void *state);

/* Fails a behavior's start with a message in the manager's log. */
int pilot_reject(chasm_ctx *c, const char *behavior, const char *reason);

#pragma GCC visibility pop
#endif
