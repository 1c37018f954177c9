/* The propeller behaviors: speed_control (closed loop on speed, setpoint_t
 * SPEED_MPS) and rpm_control (open loop, SPEED_RPM).
 *
 *   rpm = rpm_per_mps * setpoint + kp e + I,     e = setpoint - speed
 *
 * The feed-forward term gives nearly the right rpm at once (REMUS 100: about
 * 1000 rpm per m/s); the PI removes what is left (trim drag, a current). rpm
 * values are plain numbers in rev/min, as in actuators_t.prop_rpm. The law
 * is pilot_loops.c. */
#include <stdio.h>

#include "plugins/pilot/pilot.h"

/* The rpm limits at their slots (prop_start reads max_rpm right after min_rpm). */
#define RPM_LIMIT_PARAMS(min, max, slew)                                                                        \
    [min] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("min_rpm", "", -100000, 100000, "lowest prop command [rpm]"),     \
    [max] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_rpm", "", -100000, 100000, "highest prop command [rpm]"),    \
    [slew] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("rpm_slew", "", 0, 1e6, "prop slew limit [rpm/s] (0: none)")
#define PROP_OUT CHASM_WRITE("prop", CHASM_DOUBLE, "", "actuators.prop_rpm", "prop command [rpm]")

/* min_rpm <= max_rpm is a relation between two parameters, which the loader
 * cannot check: the behavior fails at start, with the reason in the log. */
static int prop_start(chasm_ctx *c, void *st, int min_slot, int prop_slot, const char *name)
{
    pilot_prop_state *s = st;
    double lo = chasm_param_double(c, min_slot), hi = chasm_param_double(c, min_slot + 1);
    if (lo > hi) {
        char why[96];
        snprintf(why, sizeof why, "min_rpm (%g) is above max_rpm (%g)", lo, hi);
        return pilot_reject(c, name, why);
    }
    pilot_prop_start(&s->loop, chasm_read_double(c, prop_slot));
    return 0;
}

/* ------------------------------------------------------------ speed_control */

const chasm_param_spec pilot_speed_control_params[S_NPARAMS] = {
    [S_SPEED] = CHASM_READ("speed", CHASM_DOUBLE, "m/s", "nav.u_mps", "measured surge speed"),
    [S_SETPOINT] = CHASM_READ("setpoint", CHASM_DOUBLE, "m/s", "setpoint.speed_mps", "desired speed"),
    [S_REFERENCE] = CHASM_READ("reference", CHASM_INT, "", "setpoint.speed_reference",
                               "setpoint_t.SPEED_OVER_GROUND (0): PI on the measured speed; SPEED_THROUGH_WATER (1): "
                               "the rpm law alone"),
    [S_PROP] = PROP_OUT,
    [S_FF] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("rpm_per_mps", "", 0, 100000,
                                               "feed-forward: prop rpm per m/s of setpoint"),
    [S_KP] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("kp", "", 0, 100000, "rpm per m/s of speed error"),
    [S_KI] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("ki", "", 0, 100000, "rpm per metre of integrated speed error"),
    [S_I_LIMIT] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("i_limit", "", 0, 100000, "largest rpm the integrator may hold"),
    RPM_LIMIT_PARAMS(S_MIN_RPM, S_MAX_RPM, S_RPM_SLEW),
};

int pilot_speed_control_start(chasm_ctx *c, void *st)
{
    return prop_start(c, st, S_MIN_RPM, S_PROP, "speed_control");
}

chasm_status_code pilot_speed_control_step(chasm_ctx *c, void *st)
{
    pilot_prop_state *s = st;
    const pilot_prop_gains g = {
        .rpm_per_mps = chasm_param_double(c, S_FF),
        .kp = chasm_param_double(c, S_KP),
        .ki = chasm_param_double(c, S_KI),
        .i_limit = chasm_param_double(c, S_I_LIMIT),
        .min_rpm = chasm_param_double(c, S_MIN_RPM),
        .max_rpm = chasm_param_double(c, S_MAX_RPM),
        .rpm_slew = chasm_param_double(c, S_RPM_SLEW),
    };
    double rpm = pilot_speed_step(&s->loop, &g, chasm_read_double(c, S_SETPOINT), chasm_read_double(c, S_SPEED),
                                  chasm_read_int(c, S_REFERENCE) == 1, c->dt_s);
    chasm_write_double(c, S_PROP, rpm);
    return CHASM_RUNNING;
}


/* -------------------------------------------------------------- rpm_control */

const chasm_param_spec pilot_rpm_control_params[R_NPARAMS] = {
    [R_SETPOINT] = CHASM_READ("setpoint", CHASM_DOUBLE, "", "setpoint.prop_rpm", "desired prop rpm"),
    [R_PROP] = PROP_OUT,
    RPM_LIMIT_PARAMS(R_MIN_RPM, R_MAX_RPM, R_RPM_SLEW),
};

int pilot_rpm_control_start(chasm_ctx *c, void *st)
{
    return prop_start(c, st, R_MIN_RPM, R_PROP, "rpm_control");
}

chasm_status_code pilot_rpm_control_step(chasm_ctx *c, void *st)
{
    pilot_prop_state *s = st;
    const pilot_prop_gains g = {
        .min_rpm = chasm_param_double(c, R_MIN_RPM),
        .max_rpm = chasm_param_double(c, R_MAX_RPM),
        .rpm_slew = chasm_param_double(c, R_RPM_SLEW),
    };
    chasm_write_double(c, R_PROP, pilot_rpm_step(&s->loop, &g, chasm_read_double(c, R_SETPOINT), c->dt_s));
    return CHASM_RUNNING;
}
