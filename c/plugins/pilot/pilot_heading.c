/* heading_control: heading -> rudder, with yaw-rate damping.
 *
 *   e      = wrap(setpoint - heading)                  (the short way round)
 *   rudder = kd (clamp(kp/kd e, +-max_turn_rate) - r) + I
 *
 * which is kp e - kd r (a PD on heading with gyro damping) while the heading
 * error is small, and a yaw-rate controller holding max_turn_rate during a
 * large turn. Why both: the REMUS 100 table model is open-loop unstable in
 * yaw (docs/simulator.md); the kd r term is what stabilises it, and limiting
 * the turn rate keeps the sideslip small enough that the rudder never runs
 * out of authority against the Munk moment. The integrator (trim: the hull
 * needs about 1 degree of rudder to run straight) only runs within i_zone of
 * the heading, so a long turn does not load it. The law is pilot_loops.c. */
#include "plugins/pilot/pilot.h"

const chasm_param_spec pilot_heading_control_params[H_NPARAMS] = {
    [H_HEADING] = CHASM_READ("heading", CHASM_DOUBLE, "rad", "nav.heading_rad", "vehicle heading"),
    [H_YAW_RATE] = CHASM_READ("yaw_rate", CHASM_DOUBLE, "rad/s", "nav.r_radps", "body yaw rate r"),
    [H_SETPOINT] = CHASM_READ("setpoint", CHASM_DOUBLE, "rad", "setpoint.heading_rad", "desired heading"),
    [H_RUDDER] = CHASM_WRITE("rudder", CHASM_DOUBLE, "rad", "actuators.rudder_rad", "rudder command"),
    [H_KP] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("kp", "", 0, 20, "rudder per heading error [rad/rad]"),
    [H_KI] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("ki", "", 0, 5, "rudder per integrated heading error [rad/(rad s)]"),
    [H_KD] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("kd", "", 0.01, 50,
                                               "rudder per yaw rate: the yaw damping [rad/(rad/s)]"),
    [H_MAX_TURN_RATE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_turn_rate", "rad/s", 0.1 * PILOT_DEG, 90 * PILOT_DEG,
                                                          "largest turn rate a heading error asks for"),
    [H_MAX_RUDDER] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_rudder", "rad", 0.5 * PILOT_DEG, 60 * PILOT_DEG,
                                                       "rudder limit"),
    [H_RUDDER_SLEW] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("rudder_slew", "rad/s", 0, 1000 * PILOT_DEG,
                                                        "rudder slew limit (0: none)"),
    [H_I_LIMIT] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("i_limit", "rad", 0, 60 * PILOT_DEG,
                                                    "largest rudder the integrator may hold"),
    [H_I_ZONE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("i_zone", "rad", 0, 180 * PILOT_DEG,
                                                   "integrate only within this heading error (0: always)"),
};

int pilot_heading_control_start(chasm_ctx *c, void *st)
{
    pilot_heading_state *s = st;
    pilot_heading_start(&s->loop, chasm_read_double(c, H_RUDDER));
    return 0;
}

chasm_status_code pilot_heading_control_step(chasm_ctx *c, void *st)
{
    pilot_heading_state *s = st;
    const pilot_heading_gains g = {
        .kp = chasm_param_double(c, H_KP),
        .ki = chasm_param_double(c, H_KI),
        .kd = chasm_param_double(c, H_KD),
        .max_turn_rate = chasm_param_double(c, H_MAX_TURN_RATE),
        .max_rudder = chasm_param_double(c, H_MAX_RUDDER),
        .rudder_slew = chasm_param_double(c, H_RUDDER_SLEW),
        .i_limit = chasm_param_double(c, H_I_LIMIT),
        .i_zone = chasm_param_double(c, H_I_ZONE),
    };
    double rudder = pilot_heading_step(&s->loop, &g, chasm_read_double(c, H_SETPOINT),
                                       chasm_read_double(c, H_HEADING), chasm_read_double(c, H_YAW_RATE), c->dt_s);
    chasm_write_double(c, H_RUDDER, rudder);
    return CHASM_RUNNING;
}
