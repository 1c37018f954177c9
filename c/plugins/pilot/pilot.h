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

/* ---- behaviors (one file each family) */
extern const chasm_behavior_spec pilot_heading_behavior;
extern const chasm_behavior_spec pilot_depth_behavior;
extern const chasm_behavior_spec pilot_altitude_behavior;
extern const chasm_behavior_spec pilot_pitch_behavior;
extern const chasm_behavior_spec pilot_speed_behavior;
extern const chasm_behavior_spec pilot_rpm_behavior;
extern const chasm_behavior_spec pilot_watch_behavior;

/* Fails a behavior's start with a message in the manager's log. */
int pilot_reject(chasm_ctx *c, const char *behavior, const char *reason);

#pragma GCC visibility pop
#endif
