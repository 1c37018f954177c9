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

enum { HEADING, YAW_RATE, SETPOINT, RUDDER, KP, KI, KD, MAX_TURN_RATE, MAX_RUDDER, RUDDER_SLEW, I_LIMIT, I_ZONE,
       NPARAMS };

static const chasm_param_spec params[NPARAMS] = {
    [HEADING] = CHASM_READ("heading", CHASM_DOUBLE, "rad", "nav.heading_rad", "vehicle heading"),
    [YAW_RATE] = CHASM_READ("yaw_rate", CHASM_DOUBLE, "rad/s", "nav.r_radps", "body yaw rate r"),
    [SETPOINT] = CHASM_READ("setpoint", CHASM_DOUBLE, "rad", "setpoint.heading_rad", "desired heading"),
    [RUDDER] = CHASM_WRITE("rudder", CHASM_DOUBLE, "rad", "actuators.rudder_rad", "rudder command"),
    [KP] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("kp", "", 0, 20, "rudder per heading error [rad/rad]"),
    [KI] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("ki", "", 0, 5, "rudder per integrated heading error [rad/(rad s)]"),
    [KD] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("kd", "", 0.01, 50, "rudder per yaw rate: the yaw damping [rad/(rad/s)]"),
    [MAX_TURN_RATE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_turn_rate", "rad/s", 0.1 * PILOT_DEG, 90 * PILOT_DEG,
                                                        "largest turn rate a heading error asks for"),
    [MAX_RUDDER] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_rudder", "rad", 0.5 * PILOT_DEG, 60 * PILOT_DEG,
                                                     "rudder limit"),
    [RUDDER_SLEW] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("rudder_slew", "rad/s", 0, 1000 * PILOT_DEG,
                                                      "rudder slew limit (0: none)"),
    [I_LIMIT] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("i_limit", "rad", 0, 60 * PILOT_DEG,
                                                  "largest rudder the integrator may hold"),
    [I_ZONE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("i_zone", "rad", 0, 180 * PILOT_DEG,
                                                 "integrate only within this heading error (0: always)"),
};

typedef struct {
    pilot_heading_loop loop;
} heading_state;

static int start(chasm_ctx *c, void *st)
{
    heading_state *s = st;
    pilot_heading_start(&s->loop, chasm_read_double(c, RUDDER));
    return 0;
}

static chasm_status_code step(chasm_ctx *c, void *st)
{
    heading_state *s = st;
    const pilot_heading_gains g = {
        .kp = chasm_param_double(c, KP),
        .ki = chasm_param_double(c, KI),
        .kd = chasm_param_double(c, KD),
        .max_turn_rate = chasm_param_double(c, MAX_TURN_RATE),
        .max_rudder = chasm_param_double(c, MAX_RUDDER),
        .rudder_slew = chasm_param_double(c, RUDDER_SLEW),
        .i_limit = chasm_param_double(c, I_LIMIT),
        .i_zone = chasm_param_double(c, I_ZONE),
    };
    double rudder = pilot_heading_step(&s->loop, &g, chasm_read_double(c, SETPOINT), chasm_read_double(c, HEADING),
                                       chasm_read_double(c, YAW_RATE), c->dt_s);
    chasm_write_double(c, RUDDER, rudder);
    return CHASM_RUNNING;
}

const chasm_behavior_spec pilot_heading_behavior = {
    "heading_control", "hold setpoint heading with the rudder (PD with yaw-rate damping, turn-rate limit)",
    params, CHASM_COUNT(params), sizeof(heading_state), start, step, NULL};
