/* The pilot plugin's behaviors, loaded from plans by the real libchasm and
 * stepped against scripted inputs: signs, limits, slew, anti-windup, wrap
 * at north, and the loader's parameter checks (file:line:col). */
#include <stdlib.h>
#include <string.h>

#include "../common/plugin_test.h"
#include "pilot_tests.h"

#define DEG (3.14159265358979323846 / 180.0)
#define PITCH_KP 1.5 /* the default stern plane per pitch error */


static const char *IO =
    "use pilot\n"
    "input nav.heading_rad : double rad\n"
    "input nav.r_radps : double rad/s\n"
    "input nav.depth_m : double m\n"
    "input nav.altitude_m : double m\n"
    "input nav.pitch_rad : double rad\n"
    "input nav.q_radps : double rad/s\n"
    "input nav.u_mps : double m/s\n"
    "input setpoint.heading_rad : double rad\n"
    "input setpoint.depth_m : double m\n"
    "input setpoint.altitude_m : double m\n"
    "input setpoint.pitch_rad : double rad\n"
    "input setpoint.speed_mps : double m/s\n"
    "input setpoint.prop_rpm : double\n"
    "output actuators.rudder_rad : double rad\n"
    "output actuators.stern_plane_rad : double rad\n"
    "output actuators.prop_rpm : double\n"
    "input setpoint.speed_reference : int\n"
    "input setpoint.utime : int\n"
    "input setpoint.vertical_mode : int\n"
    "input setpoint.speed_mode : int\n"
    "output pilot.state : int\n"
    "output pilot.speed_reference : int\n"
    "output pilot.setpoints_ignored : int\n"
    "output pilot.ignoring : bool\n"
    "output pilot.last_ignored_reason : int\n"
    "output pilot.last_ignored_utime : int\n"; /* 27 lines */

/* The plugin has no default gains (the pilot plan sets every one): the
 * tests' own values, the ones they were written against, for every
 * parameter an action leaves out. */
static const struct {
    const char *behavior, *gains;
} GAINS[] = {
    {"heading_control", "kp = 2, ki = 0.1, kd = 4, max_turn_rate = 6 deg/s, max_rudder = 20 deg, "
                        "rudder_slew = 30 deg/s, i_limit = 5 deg, i_zone = 10 deg"},
    {"depth_control", "kp = 0.25, ki = 0.02, kd = 0, max_pitch = 15 deg, pitch_slew = 5 deg/s, max_depth = 100 m, "
                      "depth_rate_tau = 1 s, pitch_kp = 1.5, pitch_ki = 0.6, pitch_kd = 5, max_plane = 20 deg, "
                      "plane_slew = 30 deg/s, plane_i_limit = 10 deg"},
    {"altitude_control", "altitude_tau = 1 s, search_rate = 0.2 m/s, kp = 0.25, ki = 0.02, kd = 0, "
                         "max_pitch = 15 deg, pitch_slew = 5 deg/s, max_depth = 100 m, depth_rate_tau = 1 s, "
                         "pitch_kp = 1.5, pitch_ki = 0.6, pitch_kd = 5, max_plane = 20 deg, plane_slew = 30 deg/s, "
                         "plane_i_limit = 10 deg"},
    {"pitch_control", "max_pitch = 30 deg, pitch_kp = 1.5, pitch_ki = 0.6, pitch_kd = 5, max_plane = 20 deg, "
                      "plane_slew = 30 deg/s, plane_i_limit = 10 deg"},
    {"speed_control", "rpm_per_mps = 1000, kp = 1000, ki = 60, i_limit = 300, min_rpm = 0, max_rpm = 2000, "
                      "rpm_slew = 500"},
    {"rpm_control", "min_rpm = 0, max_rpm = 2000, rpm_slew = 500"},
};

/* Whether `args` (the text inside the parentheses) names parameter `name`. */
static int names(const char *args, const char *name, size_t len)
{
    for (const char *p = strstr(args, name); p; p = strstr(p + 1, name)) {
        const char *after = p + len;
        while (*after == ' ')
            after++;
        if ((p == args || p[-1] == ' ' || p[-1] == '(' || p[-1] == ',') && *after == '=')
            return 1;
    }
    return 0;
}

/* `action` with the test gains it leaves out appended. */
static const char *with_gains(const char *action)
{
    static char out[2048];
    snprintf(out, sizeof out, "%s", action);
    const char *open = strchr(action, '(');
    char *close = strrchr(out, ')');
    if (!open || !close)
        return out;
    for (size_t i = 0; i < sizeof GAINS / sizeof GAINS[0]; i++) {
        size_t blen = strlen(GAINS[i].behavior);
        if ((size_t)(open - action) != blen || strncmp(action, GAINS[i].behavior, blen) != 0)
            continue;
        char extra[1024] = "";
        const char *g = GAINS[i].gains;
        while (*g) {
            const char *end = strchr(g, ',');
            size_t n = end ? (size_t)(end - g) : strlen(g);
            size_t name_len = strcspn(g, " =");
            char name[64];
            snprintf(name, sizeof name, "%.*s", (int)name_len, g);
            if (!names(open, name, name_len))
                snprintf(extra + strlen(extra), sizeof extra - strlen(extra), "%s%.*s", extra[0] ? ", " : "",
                         (int)n, g);
            g += n;
            while (*g == ',' || *g == ' ')
                g++;
        }
        if (extra[0]) {
            int empty = close[-1] == '(';
            snprintf(close, sizeof out - (size_t)(close - out), "%s%s)", empty ? "" : ", ", extra);
        }
    }
    return out;
}

/* A plan of IO plus one state running `action` (line 29), gains filled in. */
static const char *plan_with(const char *action)
{
    static char buf[8192];
    snprintf(buf, sizeof buf, "%sstate s {\n    do %s\n}\nstate stopped {\n}\n", IO, with_gains(action));
    return buf;
}

static double t_now;

/* The plan running `action`, started at t = 0 with the vehicle level, on
 * heading 0 and not turning. */
static chasm_machine *machine(const char *action)
{
    chasm_machine *m = pt_load(plan_with(action));
    if (!m)
        return NULL;
    static const char *still[] = {"nav.heading_rad", "nav.r_radps", "nav.pitch_rad", "nav.q_radps"};
    for (size_t i = 0; i < sizeof still / sizeof still[0]; i++)
        pt_set(m, still[i], 0, 0);
    pt_start(m, 0.0);
    return m;
}

/* Steps n cycles of dt from t_now, inputs held. */
static void run(chasm_machine *m, int n, double dt)
{
    for (int i = 0; i < n; i++) {
        t_now += dt;
        pt_step(m, t_now);
    }
}

void pilot_param_errors(void)
{
    const char *e = pt_errors(plan_with("heading_control(kp = 100)"));
    CHECK_HAS(e, "t.chasm:29:29: error: parameter 'kp' of 'heading_control' is 100");
    CHECK_HAS(e, "outside its range [0, 20]");
    e = pt_errors(plan_with("heading_control(max_rudder = 20)"));
    CHECK_HAS(e, "t.chasm:29:37: error: parameter 'max_rudder' of 'heading_control' needs a unit: it is an angle");
    e = pt_errors(plan_with("heading_control(max_rudder = 90 deg)"));
    CHECK_HAS(e, "t.chasm:29:37: error: parameter 'max_rudder' of 'heading_control' is 1.5708 rad, outside its range");
    e = pt_errors(plan_with("heading_control(rudder = actuators.prop_rpm)"));
    CHECK_HAS(e, "t.chasm:29:33: error: parameter 'rudder' of 'heading_control' expects a variable in 'rad'");
    e = pt_errors(plan_with("depth_control(kpp = 1)"));
    CHECK_HAS(e, "t.chasm:29:22: error: unknown parameter 'kpp' for 'depth_control' (did you mean 'kp'?)");
    e = pt_errors(plan_with("speed_control(rpm_slew = -5)"));
    CHECK_HAS(e, "t.chasm:29:33: error: parameter 'rpm_slew' of 'speed_control' is -5");
    e = pt_errors(plan_with("altitude_control(search_rate = 1 m)"));
    CHECK_HAS(e, "t.chasm:29:39: error: parameter 'search_rate' of 'altitude_control' is a speed (m/s), but 'm' is a length");
    /* the default variables must be declared: a plan without nav.r_radps */
    e = pt_errors("use pilot\ninput nav.heading_rad : double rad\ninput setpoint.heading_rad : double rad\n"
                  "output actuators.rudder_rad : double rad\nstate s {\n    do heading_control()\n}\n");
    CHECK_HAS(e, "t.chasm:6:8: error: 'heading_control' reads variable 'nav.r_radps' (its default for 'yaw_rate')");
    /* and the good plan loads */
    CHECK(strcmp(pt_errors(plan_with("heading_control(kp = 2, kd = 4, max_rudder = 15 deg)")), "") == 0);
    /* no gain has a default: the pilot plan is the one place they are set */
    char plan[4096];
    snprintf(plan, sizeof plan, "%sstate s {\n    do heading_control(kp = 2)\n}\n", IO);
    e = pt_errors(plan);
    CHECK_HAS(e, "t.chasm:29:8: error: 'heading_control' needs parameter 'kd'");
    CHECK_HAS(e, "'heading_control' needs parameter 'max_rudder'");
    snprintf(plan, sizeof plan, "%sstate s {\n    do speed_control()\n}\n", IO);
    CHECK_HAS(pt_errors(plan), "'speed_control' needs parameter 'rpm_per_mps'");
}

static double rudder_for(double heading_deg, double setpoint_deg)
{
    chasm_machine *m = machine("heading_control(kp = 2, ki = 0, kd = 4, rudder_slew = 0 deg/s)");
    if (!m)
        return NAN;
    pt_set(m, "nav.heading_rad", heading_deg * DEG, 0);
    pt_set(m, "setpoint.heading_rad", setpoint_deg * DEG, 0);
    run(m, 3, 0.05);
    double r = pt_get(m, "actuators.rudder_rad");
    chasm_free(m);
    return r;
}

void pilot_heading_wraps_at_north(void)
{
    /* 2 degrees to starboard, across north and away from it: same command */
    double across = rudder_for(359, 1), plain = rudder_for(10, 12);
    CHECK(across > 0.0);                                   /* positive rudder: bow to starboard */
    CHECK_NEAR(across, plain, 1e-9);
    CHECK_NEAR(across, 2 * 2 * DEG, 1e-9);                 /* kp e */
    CHECK_NEAR(rudder_for(1, 359), -plain, 1e-9);          /* and to port */
    CHECK_NEAR(rudder_for(0, 360), 0.0, 1e-12);            /* 360 is north */
    CHECK_NEAR(rudder_for(180, 179), -2 * DEG, 1e-9);      /* no jump at 180 either */
    CHECK_NEAR(rudder_for(179, 181), 2 * 2 * DEG, 1e-9);
}

void pilot_heading_limits_and_slew(void)
{
    chasm_machine *m = machine("heading_control(kp = 5, ki = 0, kd = 4, max_turn_rate = 90 deg/s, "
                               "max_rudder = 15 deg, rudder_slew = 20 deg/s)");
    if (!m)
        return;
    pt_set(m, "actuators.rudder_rad", 0, 0);
    pt_set(m, "setpoint.heading_rad", 90 * DEG, 0);
    double prev = 0;
    int cycles = 0;
    for (int i = 0; i < 40; i++) {
        run(m, 1, 0.05);
        double r = pt_get(m, "actuators.rudder_rad");
        CHECK(r - prev <= 20 * DEG * 0.05 + 1e-9);          /* slew: 1 degree per 50 ms cycle */
        CHECK(r <= 15 * DEG + 1e-12);                        /* limit */
        if (r < 15 * DEG - 1e-9)
            cycles++;
        prev = r;
    }
    CHECK_NEAR(prev, 15 * DEG, 1e-9);
    CHECK(cycles >= 15 && cycles <= 16);                     /* 15 degrees at 1 degree per cycle */
    chasm_free(m);
}

void pilot_heading_turn_rate_limit(void)
{
    /* A 90 degree error asks for max_turn_rate, not for full rudder:
     * rudder = kd (max_turn_rate - r). */
    chasm_machine *m = machine("heading_control(kp = 2, ki = 0, kd = 4, max_turn_rate = 5 deg/s, "
                               "rudder_slew = 0 deg/s)");
    if (!m)
        return;
    pt_set(m, "setpoint.heading_rad", 90 * DEG, 0);
    run(m, 2, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.rudder_rad"), 4 * 5 * DEG, 1e-9);
    pt_set(m, "nav.r_radps", 5 * DEG, t_now);                 /* turning at the limit: no more rudder */
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.rudder_rad"), 0.0, 1e-9);
    pt_set(m, "nav.r_radps", 8 * DEG, t_now);                 /* too fast: counter-rudder (damping) */
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.rudder_rad"), -4 * 3 * DEG, 1e-9);
    pt_set(m, "setpoint.heading_rad", 0, t_now);              /* on heading, still turning */
    pt_set(m, "nav.r_radps", 2 * DEG, t_now);
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.rudder_rad"), -4 * 2 * DEG, 1e-9);
    chasm_free(m);
}

void pilot_heading_trim_integrator(void)
{
    /* A steady 1 degree error: the integrator builds rudder (ki = 0.1 per s);
     * a large error (beyond i_zone, or beyond the turn-rate clamp) does not. */
    chasm_machine *m = machine("heading_control(kp = 0.001, ki = 0.1, kd = 4, i_zone = 10 deg, "
                               "rudder_slew = 0 deg/s)");
    if (!m)
        return;
    pt_set(m, "setpoint.heading_rad", 1 * DEG, 0);
    run(m, 201, 0.05);                                        /* 10 s after the first (dt = 0) cycle */
    CHECK_NEAR(pt_get(m, "actuators.rudder_rad"), 0.001 * DEG + 0.1 * 1 * DEG * 10, 1e-9);
    chasm_free(m);
    m = machine("heading_control(kp = 2, ki = 0.1, kd = 4, i_zone = 10 deg, max_turn_rate = 3 deg/s, "
                "rudder_slew = 0 deg/s)");
    if (!m)
        return;
    pt_set(m, "setpoint.heading_rad", 45 * DEG, 0);
    run(m, 200, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.rudder_rad"), 4 * 3 * DEG, 1e-9); /* kd * max_turn_rate, no I */
    chasm_free(m);
}

/* depth_control without slew limits, with `extra` parameters (", kp = 1"). */
static chasm_machine *depth_machine(const char *extra)
{
    char action[512];
    snprintf(action, sizeof action, "depth_control(pitch_slew = 0 deg/s, plane_slew = 0 deg/s%s)", extra);
    return machine(action);
}

void pilot_depth_cascade_signs(void)
{
    chasm_machine *m = depth_machine(", kp = 0.25, ki = 0, pitch_ki = 0, max_plane = 45 deg");
    if (!m)
        return;
    pt_set(m, "nav.depth_m", 2, 0);
    pt_set(m, "setpoint.depth_m", 10, 0);
    run(m, 2, 0.05);
    /* too shallow: bow down: pitch command -15 deg (clamped), plane PITCH_KP * 15 deg */
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), PITCH_KP * 15 * DEG, 1e-9);
    pt_set(m, "nav.depth_m", 10.2, t_now);                    /* 0.2 m too deep: bow up */
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), -PITCH_KP * 0.25 * 0.2, 1e-9);
    pt_set(m, "nav.depth_m", 10, t_now);
    pt_set(m, "nav.pitch_rad", -5 * DEG, t_now);              /* on depth but bow down: raise it */
    pt_set(m, "nav.q_radps", -2 * DEG, t_now);                /* and still pitching down: damp */
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), -(PITCH_KP * 5 * DEG + 5 * 2 * DEG), 1e-9);
    pt_set(m, "setpoint.depth_m", 500, t_now);                /* beyond max_depth (100 m) */
    pt_set(m, "nav.depth_m", 100, t_now);
    pt_set(m, "nav.pitch_rad", 0, t_now);
    pt_set(m, "nav.q_radps", 0, t_now);
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), 0.0, 1e-9);
    chasm_free(m);
}

void pilot_depth_anti_windup(void)
{
    /* 100 s far too shallow (pitch command saturated at -15 deg, the vehicle
     * stuck level), then 1 m too deep: the plane reverses within a cycle. */
    chasm_machine *m = depth_machine(", kp = 0.25, ki = 0.05");
    if (!m)
        return;
    pt_set(m, "nav.depth_m", 0, 0);
    pt_set(m, "setpoint.depth_m", 50, 0);
    run(m, 2000, 0.05);
    double down = pt_get(m, "actuators.stern_plane_rad");
    CHECK_NEAR(down, 20 * DEG, 1e-9);                         /* max_plane: the pitch loop saturated too */
    pt_set(m, "nav.depth_m", 51, t_now);
    run(m, 1, 0.05);
    CHECK(pt_get(m, "actuators.stern_plane_rad") < 0.0);     /* bow up at once: nothing wound up */
    chasm_free(m);
}

void pilot_depth_pitch_slew(void)
{
    /* the pitch command ramps at pitch_slew (5 deg/s by default): with a
     * level vehicle the plane (PITCH_KP, no I) follows the ramp */
    chasm_machine *m = machine("depth_control(ki = 0, pitch_ki = 0, plane_slew = 0 deg/s)");
    if (!m)
        return;
    pt_set(m, "nav.depth_m", 2, 0);
    pt_set(m, "setpoint.depth_m", 10, 0);
    run(m, 1, 0.05);                                          /* first cycle: dt 0, holds the start pitch */
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), 0.0, 1e-12);
    run(m, 20, 0.05);                                         /* 1 s: -5 deg of pitch command */
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), PITCH_KP * 5 * DEG, 1e-9);
    chasm_free(m);
}

void pilot_pitch_control(void)
{
    chasm_machine *m = machine("pitch_control(max_pitch = 10 deg, pitch_ki = 0, plane_slew = 0 deg/s, max_plane = 45 deg)");
    if (!m)
        return;
    pt_set(m, "setpoint.pitch_rad", 30 * DEG, 0);             /* clamped to 10 deg, bow up */
    run(m, 2, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), -PITCH_KP * 10 * DEG, 1e-9);
    pt_set(m, "setpoint.pitch_rad", -30 * DEG, t_now);        /* and bow down */
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), PITCH_KP * 10 * DEG, 1e-9);
    chasm_free(m);
}

void pilot_altitude_target_and_search(void)
{
    /* no filtering, no integrator, no slews: the plane shows the depth target */
    chasm_machine *m = machine("altitude_control(altitude_tau = 0 s, ki = 0, kp = 0.01, pitch_ki = 0, "
                               "pitch_slew = 0 deg/s, plane_slew = 0 deg/s, search_rate = 0.5 m/s)");
    if (!m)
        return;
    pt_set(m, "nav.depth_m", 20, 0);
    pt_set(m, "nav.altitude_m", 12, 0);                       /* seabed at 32 m */
    pt_set(m, "setpoint.altitude_m", 8, 0);                   /* target: 24 m, 4 m deeper */
    run(m, 2, 0.05);
    const double per_m = PITCH_KP * 0.01;                     /* plane per metre of depth error */
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), per_m * 4, 1e-9);
    /* the altitude goes unknown (-1): the target moves down at 0.5 m/s from
     * where it was (24 m), never more than 2 m below the vehicle (20 m) */
    pt_set(m, "nav.altitude_m", -1, t_now);
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), per_m * 4, 1e-9);  /* already below 22 m: held */
    chasm_free(m);
    m = machine("altitude_control(altitude_tau = 0 s, ki = 0, kp = 0.01, pitch_ki = 0, "
                "pitch_slew = 0 deg/s, plane_slew = 0 deg/s, search_rate = 0.5 m/s)");
    if (!m)
        return;
    pt_set(m, "nav.depth_m", 5, 0);
    pt_set(m, "nav.altitude_m", -1, 0);                       /* no bottom lock from the start */
    pt_set(m, "setpoint.altitude_m", 8, 0);
    run(m, 1, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), 0.0, 1e-9);        /* starts from here */
    run(m, 40, 0.05);                                         /* 2 s at 0.5 m/s: 1 m deeper */
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), per_m * 1.0, 1e-9);
    run(m, 200, 0.05);                                        /* capped at 2 m below the vehicle */
    CHECK_NEAR(pt_get(m, "actuators.stern_plane_rad"), per_m * 2.0, 1e-9);
    pt_set(m, "nav.altitude_m", NAN, t_now);                  /* not a number counts as unknown */
    run(m, 1, 0.05);
    CHECK(isfinite(pt_get(m, "actuators.stern_plane_rad")));
    chasm_free(m);
}

void pilot_speed_feed_forward_and_stop(void)
{
    chasm_machine *m = machine("speed_control(rpm_slew = 0)");
    if (!m)
        return;
    pt_set(m, "nav.u_mps", 1.5, 0);
    pt_set(m, "setpoint.speed_mps", 1.5, 0);
    run(m, 2, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.prop_rpm"), 1500, 1e-9);  /* on speed: feed-forward only */
    pt_set(m, "nav.u_mps", 1.4, t_now);                       /* 0.1 m/s slow: kp 1000, ki 60 */
    run(m, 20, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.prop_rpm"), 1500 + 100 + 60 * 0.1 * 1.0, 1e-6);
    pt_set(m, "setpoint.speed_mps", 0, t_now);                /* stop means 0 rpm, not a PI */
    run(m, 1, 0.05);
    CHECK(pt_get(m, "actuators.prop_rpm") == 0.0);
    pt_set(m, "setpoint.speed_mps", 5, t_now);                /* asks too much: max_rpm */
    run(m, 1, 0.05);
    CHECK(pt_get(m, "actuators.prop_rpm") == 2000.0);
    chasm_free(m);
    /* the slew limit (500 rpm/s by default) from the current command */
    m = machine("speed_control()");
    if (!m)
        return;
    pt_set(m, "nav.u_mps", 0, 0);
    pt_set(m, "setpoint.speed_mps", 1.5, 0);
    run(m, 21, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.prop_rpm"), 500, 1e-6);
    chasm_free(m);
}

void pilot_rpm_limits(void)
{
    chasm_machine *m = machine("rpm_control(min_rpm = -500, max_rpm = 1800, rpm_slew = 1000)");
    if (!m)
        return;
    pt_set(m, "actuators.prop_rpm", 0, 0);
    pt_set(m, "setpoint.prop_rpm", 1200, 0);
    run(m, 11, 0.05);                                         /* 0.5 s at 1000 rpm/s */
    CHECK_NEAR(pt_get(m, "actuators.prop_rpm"), 500, 1e-6);
    run(m, 40, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.prop_rpm"), 1200, 1e-9);
    pt_set(m, "setpoint.prop_rpm", 9000, t_now);
    run(m, 40, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.prop_rpm"), 1800, 1e-9);
    pt_set(m, "setpoint.prop_rpm", -9000, t_now);
    run(m, 100, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.prop_rpm"), -500, 1e-9);
    chasm_free(m);
}

void pilot_bad_rpm_limits_fail_at_start(void)
{
    /* min_rpm > max_rpm: two values each in range, wrong together. The
     * loader cannot see it; the behavior fails at start, with the reason in
     * the log, and the plan's `when failed` catches it. */
    char plan[4096];
    snprintf(plan, sizeof plan, "%sstate s {\n    do rpm_control(min_rpm = 500, max_rpm = 100, rpm_slew = 500)\n"
                                "    when failed -> stopped\n}\nstate stopped {\n}\n", IO);
    chasm_machine *m = pt_load(plan);
    if (!m)
        return;
    pt_start(m, 0);
    pt_step(m, 0.05);
    CHECK(strcmp(pt_leaf(m), "stopped") == 0);
    CHECK_HAS(pt_log, "rpm_control: min_rpm (500) is above max_rpm (100)");
    chasm_free(m);
}

void pilot_speed_through_the_water(void)
{
    /* setpoint_t.SPEED_THROUGH_WATER: the rpm law alone, whatever the
     * (over-ground) navigation speed says: a head current is not fought */
    chasm_machine *m = machine("speed_control(rpm_slew = 0)");
    if (!m)
        return;
    pt_set_int(m, "setpoint.speed_reference", 1, 0);
    pt_set(m, "nav.u_mps", 1.2, 0);
    pt_set(m, "setpoint.speed_mps", 1.5, 0);
    run(m, 40, 0.05);
    CHECK_NEAR(pt_get(m, "actuators.prop_rpm"), 1500, 1e-9);
    pt_set_int(m, "setpoint.speed_reference", 0, t_now);        /* over ground: PI on the 0.3 m/s */
    run(m, 2, 0.05);
    CHECK(pt_get(m, "actuators.prop_rpm") > 1500 + 250);
    chasm_free(m);
}

void pilot_setpoint_watch_counts_ignored(void)
{
    chasm_machine *m = machine("setpoint_watch(timeout = 1 s, flying = true)");
    if (!m)
        return;
    run(m, 3, 0.05);                                            /* no setpoint yet: nothing to judge */
    CHECK(pt_get(m, "pilot.setpoints_ignored") == 0 && pt_get(m, "pilot.state") == 1);
    pt_set_int(m, "setpoint.utime", 0, 0);                       /* stamped 0, as the manager does */
    pt_set(m, "setpoint.heading_rad", 1.0, 0);
    run(m, 3, 0.05);                                            /* seen once, counted once */
    CHECK(pt_get(m, "pilot.setpoints_ignored") == 1 && pt_get(m, "pilot.ignoring") == 1);
    CHECK(pt_get(m, "pilot.last_ignored_reason") == 1);
    CHECK_HAS(pt_log, "setpoint ignored (utime 0, utime 0); 1 so far");
    pt_set(m, "setpoint.heading_rad", 2.0, 0);                  /* another one, still stamped 0 */
    run(m, 1, 0.05);
    CHECK(pt_get(m, "pilot.setpoints_ignored") == 2);
    long fresh = (long)(t_now * 1e6);
    pt_set_int(m, "setpoint.utime", fresh, t_now);              /* a good one: not counted */
    run(m, 1, 0.05);
    CHECK(pt_get(m, "pilot.setpoints_ignored") == 2 && pt_get(m, "pilot.ignoring") == 0);
    long old = (long)((t_now - 5.0) * 1e6);
    pt_set_int(m, "setpoint.utime", old, t_now - 5.0);          /* 5 s old on arrival */
    run(m, 1, 0.05);
    CHECK(pt_get(m, "pilot.setpoints_ignored") == 3 && pt_get(m, "pilot.last_ignored_reason") == 2);
    CHECK(pt_get(m, "pilot.last_ignored_utime") == (double)old);
    chasm_free(m);
    /* the count lives in the output: a new instance (idle <-> fly) carries it on */
    m = machine("setpoint_watch(timeout = 1 s, flying = false)");
    if (!m)
        return;
    pt_set_int(m, "pilot.setpoints_ignored", 7, 0);
    pt_set_int(m, "setpoint.utime", 0, 0);
    run(m, 1, 0.05);
    CHECK(pt_get(m, "pilot.setpoints_ignored") == 8 && pt_get(m, "pilot.state") == 0);
    chasm_free(m);
}
