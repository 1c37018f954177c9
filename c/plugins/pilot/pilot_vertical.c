/* The vertical behaviors: depth_control, altitude_control and pitch_control,
 * all driving the stern plane through the shared loops of pilot_loops.c. */
#include <math.h>

#include "plugins/pilot/pilot.h"

/* Entries all three share. */
#define PITCH_IN CHASM_READ("pitch", CHASM_DOUBLE, "rad", "nav.pitch_rad", "vehicle pitch, positive bow up")
#define Q_IN CHASM_READ("pitch_rate", CHASM_DOUBLE, "rad/s", "nav.q_radps", "body pitch rate q")
#define DEPTH_IN CHASM_READ("depth", CHASM_DOUBLE, "m", "nav.depth_m", "vehicle depth")
#define PLANE_OUT CHASM_WRITE("stern_plane", CHASM_DOUBLE, "rad", "actuators.stern_plane_rad", "stern plane command")

/* ------------------------------------------------------------ depth_control */

const chasm_param_spec pilot_depth_control_params[D_NPARAMS] = {
    [D_DEPTH] = DEPTH_IN,
    [D_PITCH] = PITCH_IN,
    [D_Q] = Q_IN,
    [D_SETPOINT] = CHASM_READ("setpoint", CHASM_DOUBLE, "m", "setpoint.depth_m", "desired depth"),
    [D_PLANE] = PLANE_OUT,
    PILOT_DEPTH_LOOP_PARAMS(D_LOOP),
    PILOT_PITCH_LOOP_PARAMS(D_PITCH_LOOP),
};

int pilot_depth_control_start(chasm_ctx *c, void *st)
{
    pilot_depth_state *s = st;
    pilot_depth_start(&s->loop, chasm_read_double(c, D_PITCH), chasm_read_double(c, D_PLANE));
    return 0;
}

chasm_status_code pilot_depth_control_step(chasm_ctx *c, void *st)
{
    pilot_depth_state *s = st;
    pilot_depth_gains cfg;
    pilot_depth_gains_read(c, D_LOOP, D_PITCH_LOOP, &cfg);
    double plane = pilot_depth_step(&s->loop, &cfg, chasm_read_double(c, D_SETPOINT), chasm_read_double(c, D_DEPTH),
                                    chasm_read_double(c, D_PITCH), chasm_read_double(c, D_Q), c->dt_s);
    chasm_write_double(c, D_PLANE, plane);
    return CHASM_RUNNING;
}


/* --------------------------------------------------------- altitude_control
 *
 * Terrain following through the depth loop: the depth target is where the
 * vehicle would be at the desired altitude, depth + (altitude - setpoint),
 * low-pass filtered (altitude_tau) against altimeter noise and seabed
 * roughness. With no valid altitude (negative: no bottom lock, or not a
 * number) the target moves down at search_rate, at most SEARCH_LEAD_M below
 * the vehicle, until the seabed comes into range (0: hold the last target). */

#define SEARCH_LEAD_M 2.0

const chasm_param_spec pilot_altitude_control_params[A_NPARAMS] = {
    [A_DEPTH] = DEPTH_IN,
    [A_ALTITUDE] = CHASM_READ("altitude", CHASM_DOUBLE, "m", "nav.altitude_m",
                              "height above the seabed, negative if unknown"),
    [A_PITCH] = PITCH_IN,
    [A_Q] = Q_IN,
    [A_SETPOINT] = CHASM_READ("setpoint", CHASM_DOUBLE, "m", "setpoint.altitude_m", "desired altitude"),
    [A_PLANE] = PLANE_OUT,
    [A_TAU] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("altitude_tau", "s", 0, 60,
                                                "low-pass time constant of the depth target (0: none)"),
    [A_SEARCH] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE(
        "search_rate", "m/s", 0, 2, "descent rate of the target while the altitude is unknown (0: hold)"),
    PILOT_DEPTH_LOOP_PARAMS(A_LOOP),
    PILOT_PITCH_LOOP_PARAMS(A_PITCH_LOOP),
};

int pilot_altitude_control_start(chasm_ctx *c, void *st)
{
    pilot_altitude_state *s = st;
    pilot_depth_start(&s->loop, chasm_read_double(c, A_PITCH), chasm_read_double(c, A_PLANE));
    pu_lowpass_reset(&s->target);
    return 0;
}

chasm_status_code pilot_altitude_control_step(chasm_ctx *c, void *st)
{
    pilot_altitude_state *s = st;
    pilot_depth_gains cfg;
    pilot_depth_gains_read(c, A_LOOP, A_PITCH_LOOP, &cfg);
    double depth = chasm_read_double(c, A_DEPTH), altitude = chasm_read_double(c, A_ALTITUDE);
    double dt = c->dt_s;
    if (isfinite(depth) && isfinite(altitude) && altitude >= 0.0) {
        double raw = depth + altitude - chasm_read_double(c, A_SETPOINT);
        pu_lowpass_step(&s->target, pu_clamp(raw, 0.0, cfg.max_depth), chasm_param_double(c, A_TAU), dt);
    } else if (isfinite(depth)) {
        /* searching: move the target down, never more than SEARCH_LEAD_M
         * below the vehicle, so it is not far off when the seabed appears */
        if (!s->target.primed)
            pu_lowpass_step(&s->target, depth, 0.0, dt);
        else if (dt > 0.0)
            s->target.y = fmin(s->target.y + chasm_param_double(c, A_SEARCH) * dt,
                               fmax(s->target.y, depth + SEARCH_LEAD_M));
    }
    if (s->target.primed)
        s->target.y = pu_clamp(s->target.y, 0.0, cfg.max_depth);
    double target = s->target.primed ? s->target.y : depth;
    double plane = pilot_depth_step(&s->loop, &cfg, target, depth, chasm_read_double(c, A_PITCH),
                                    chasm_read_double(c, A_Q), dt);
    chasm_write_double(c, A_PLANE, plane);
    return CHASM_RUNNING;
}


/* ------------------------------------------------------------ pitch_control */

const chasm_param_spec pilot_pitch_control_params[P_NPARAMS] = {
    [P_PITCH] = PITCH_IN,
    [P_Q] = Q_IN,
    [P_SETPOINT] = CHASM_READ("setpoint", CHASM_DOUBLE, "rad", "setpoint.pitch_rad", "desired pitch, positive bow up"),
    [P_PLANE] = PLANE_OUT,
    [P_MAX_PITCH] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("max_pitch", "rad", 0.5 * PILOT_DEG, 80 * PILOT_DEG,
                                                      "the setpoint is clamped to +-max_pitch"),
    PILOT_PITCH_LOOP_PARAMS(P_LOOP),
};

int pilot_pitch_control_start(chasm_ctx *c, void *st)
{
    pilot_pitch_state *s = st;
    pilot_pitch_start(&s->loop, chasm_read_double(c, P_PLANE));
    return 0;
}

chasm_status_code pilot_pitch_control_step(chasm_ctx *c, void *st)
{
    pilot_pitch_state *s = st;
    pilot_pitch_gains cfg;
    pilot_pitch_gains_read(c, P_LOOP, &cfg);
    double plane = pilot_pitch_hold(&s->loop, &cfg, chasm_param_double(c, P_MAX_PITCH),
                                    chasm_read_double(c, P_SETPOINT), chasm_read_double(c, P_PITCH),
                                    chasm_read_double(c, P_Q), c->dt_s);
    chasm_write_double(c, P_PLANE, plane);
    return CHASM_RUNNING;
}
