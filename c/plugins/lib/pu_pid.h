/* pu_pid.h: a PID controller for plugins (c/plugins/lib, linked into every plugin).
 *
 *   u = feedforward + kp e + I + kd e'        then clamped to [out_min, out_max]
 *                                             then slew-limited to rate_max per s
 *
 * I is the integrator's contribution to the output (the sum of ki e dt), kept
 * in output units so that changing ki does not make the output jump and so
 * that it can be bounded directly (i_limit).
 *
 * Anti-windup (conditional integration): a step whose output ends up clamped
 * or slew-limited does not integrate an error that pushes further into that
 * limit; it still integrates an error that pulls the output back. So after a
 * long saturation the controller leaves the limit as soon as the error
 * changes sign, with no stored-up overshoot. Integral separation: with
 * i_zone > 0 the integrator only runs while |error| <= i_zone, so a large
 * transient (a 90 degree turn under a turn-rate limit, whose output is not
 * saturated) does not load it.
 *
 * The derivative is the caller's: pass a measured rate where there is one
 * (for a heading error e = psi_cmd - psi, e' = -r from the gyro: no
 * derivative kick on setpoint steps, no noise from differencing), or NAN to
 * have the PID difference the error itself (0 on the first step).
 *
 * Typical use in a behavior (state zeroed at state entry):
 *   start:  pu_pid_reset(&s->pid); pu_pid_preset_output(&s->pid, current_actuator);
 *   step:   u = pu_pid_step(&s->pid, &cfg, error, rate, ff, ctx->dt_s);
 */
#ifndef PU_PID_H
#define PU_PID_H

#include <stddef.h>

#include "plugins/lib/pu_visibility.h"

typedef struct {
    double kp;               /* output per unit of error */
    double ki;               /* output per unit of error and second (>= 0) */
    double kd;               /* output per unit of error rate (error/s) */
    double out_min, out_max; /* output limits, out_min <= out_max */
    double rate_max;         /* output slew limit per second; <= 0: none */
    double i_limit;          /* |I| <= i_limit; <= 0: I is bounded by the output range only */
    double i_zone;           /* integrate only while |error| <= i_zone; <= 0: always */
} pu_pid_config;

typedef struct {
    double integral;         /* I, in output units */
    double prev_error;
    double output;           /* the last output returned */
    int has_prev_error;
    int has_output;          /* output is valid: the slew limit starts from it */
    int limited;             /* the last output was clamped or slew-limited */
} pu_pid;

/* Forget everything (integral, last output, last error). */
PU_HIDDEN void pu_pid_reset(pu_pid *p);
/* Make the slew limit start from output (e.g. the actuator's current command):
 * a bumpless start when a behavior takes over an actuator. */
PU_HIDDEN void pu_pid_preset_output(pu_pid *p, double output);
/* One control step over dt seconds (dt <= 0, e.g. the first cycle after a
 * state entry: no integration, and the output holds a preset value).
 * derivative: d(error)/dt or NAN (see above). Non-finite error or feedforward
 * hold the last output (or give the clamped 0 if there is none) and change
 * nothing, so one bad sample cannot poison the integrator. */
PU_HIDDEN double pu_pid_step(pu_pid *p, const pu_pid_config *c, double error, double derivative,
                             double feedforward, double dt);
/* Checks a configuration; returns 0, or -1 with a one-line reason in err. */
PU_HIDDEN int pu_pid_config_check(const pu_pid_config *c, char *err, size_t errlen);

#endif
