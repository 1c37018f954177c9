/* The shared plugin lib (c/plugins/lib): angle wrapping, limits, and the PID
 * against scripted inputs and a simulated first-order plant. */
#include "plugins/lib/pu_angle.h"
#include "plugins/lib/pu_limit.h"
#include "plugins/lib/pu_pid.h"
#include "../common/plugin_test.h"

#define TWO_PI (2 * PU_PI)


void lib_angle_wrap(void)
{
    CHECK_NEAR(pu_wrap_2pi(-0.1), TWO_PI - 0.1, 1e-12);
    CHECK(pu_wrap_2pi(TWO_PI) == 0.0);
    CHECK(pu_wrap_2pi(-1e-18) == 0.0);             /* never returns 2pi itself */
    CHECK_NEAR(pu_wrap_2pi(100 * PU_PI + 0.3), 0.3, 1e-9);
    CHECK_NEAR(pu_wrap_pi(PU_PI), PU_PI, 1e-12);   /* (-pi, pi] */
    CHECK_NEAR(pu_wrap_pi(-PU_PI), PU_PI, 1e-12);
    CHECK_NEAR(pu_wrap_pi(3 * PU_PI / 2), -PU_PI / 2, 1e-12);
    /* across north, both ways, the short way round */
    CHECK_NEAR(pu_angle_diff(0.1, TWO_PI - 0.1), 0.2, 1e-12);
    CHECK_NEAR(pu_angle_diff(TWO_PI - 0.1, 0.1), -0.2, 1e-12);
    CHECK_NEAR(pu_angle_diff(1.0, 0.5), 0.5, 1e-12);
    CHECK(isnan(pu_wrap_pi(NAN)));
}

void lib_clamp_and_slew(void)
{
    CHECK(pu_clamp(5, -1, 2) == 2 && pu_clamp(-5, -1, 2) == -1 && pu_clamp(0.5, -1, 2) == 0.5);
    CHECK(pu_clamp(NAN, -1, 2) == -1);             /* NaN never reaches an actuator */
    CHECK(pu_clamp_sym(-3, 2) == -2);
    CHECK_NEAR(pu_rate_limit(0, 10, 2, 0.1), 0.2, 1e-12);
    CHECK_NEAR(pu_rate_limit(0, -10, 2, 0.1), -0.2, 1e-12);
    CHECK(pu_rate_limit(0, 0.05, 2, 0.1) == 0.05);  /* within the step: reached */
    CHECK(pu_rate_limit(1, 10, 0, 0.1) == 10);      /* 0: no limit */
    CHECK(pu_rate_limit(1, 10, 2, 0) == 1);         /* no time, no change */
}

void lib_lowpass(void)
{
    pu_lowpass f;
    pu_lowpass_reset(&f);
    CHECK(pu_lowpass_step(&f, 3.0, 1.0, 0.1) == 3.0); /* the first sample primes it */
    double y = 0;
    for (int i = 0; i < 10; i++)
        y = pu_lowpass_step(&f, 4.0, 1.0, 0.1);       /* one time constant */
    CHECK_NEAR(y, 4.0 - exp(-1.0), 1e-9);              /* exact discretisation */
    CHECK(pu_lowpass_step(&f, 9.0, 0.0, 0.1) == 9.0);  /* tau 0: no filtering */
}

/* y' = (g u - y) / tau, stepped exactly over dt with u held. */
static double plant(double y, double u, double g, double tau, double dt)
{
    return g * u + (y - g * u) * exp(-dt / tau);
}

void lib_pid_step_response(void)
{
    const double dt = 0.05;
    /* P only: steady error 1 / (1 + kp g) */
    pu_pid_config p_only = {.kp = 4, .out_min = -100, .out_max = 100};
    pu_pid pid;
    pu_pid_reset(&pid);
    double y = 0;
    for (int i = 0; i < 2000; i++)
        y = plant(y, pu_pid_step(&pid, &p_only, 1.0 - y, NAN, 0, dt), 1.0, 2.0, dt);
    CHECK_NEAR(y, 4.0 / 5.0, 1e-6);
    /* PI: no steady error; the first-order loop with kp g = 4, ki = 2 is
     * well damped: a small overshoot, settled (2 %) within 10 s */
    pu_pid_config pi = {.kp = 4, .ki = 2, .out_min = -100, .out_max = 100};
    pu_pid_reset(&pid);
    y = 0;
    double peak = 0, settled_at = -1;
    for (int i = 1; i <= 600; i++) {
        y = plant(y, pu_pid_step(&pid, &pi, 1.0 - y, NAN, 0, dt), 1.0, 2.0, dt);
        peak = fmax(peak, y);
        if (fabs(y - 1.0) > 0.02)
            settled_at = i * dt;
    }
    CHECK_NEAR(y, 1.0, 1e-6);
    CHECK(peak < 1.10);
    CHECK(settled_at < 10.0);
    CHECK_NEAR(pid.integral, 1.0, 1e-5);            /* holds the plant's input at steady state */
    /* feed-forward adds straight to the output */
    pu_pid_reset(&pid);
    CHECK_NEAR(pu_pid_step(&pid, &p_only, 0.5, NAN, 3.0, dt), 3.0 + 4 * 0.5, 1e-12);
    /* the derivative: the caller's rate, or the PID's own difference */
    pu_pid_config pd = {.kp = 0, .kd = 2, .out_min = -100, .out_max = 100};
    pu_pid_reset(&pid);
    CHECK(pu_pid_step(&pid, &pd, 1.0, -0.25, 0, dt) == -0.5);
    pu_pid_reset(&pid);
    CHECK(pu_pid_step(&pid, &pd, 1.0, NAN, 0, dt) == 0.0);    /* nothing to difference yet */
    CHECK_NEAR(pu_pid_step(&pid, &pd, 1.1, NAN, 0, dt), 2 * 0.1 / dt, 1e-9);
}

void lib_pid_saturation(void)
{
    pu_pid_config c = {.kp = 10, .ki = 5, .kd = 1, .out_min = -0.3, .out_max = 0.5};
    pu_pid pid;
    pu_pid_reset(&pid);
    for (int i = 0; i < 500; i++) {
        double e = 20 * sin(i * 0.05);
        double u = pu_pid_step(&pid, &c, e, NAN, 0, 0.1);
        CHECK(u >= -0.3 && u <= 0.5);
        CHECK(pid.limited == (u == -0.3 || u == 0.5));
    }
}

void lib_pid_anti_windup(void)
{
    /* 60 s at the limit with a large error, then the error changes sign */
    pu_pid_config c = {.kp = 1, .ki = 0.5, .out_min = -1, .out_max = 1};
    pu_pid pid;
    pu_pid_reset(&pid);
    for (int i = 0; i < 600; i++)
        CHECK(pu_pid_step(&pid, &c, 5.0, NAN, 0, 0.1) == 1.0);
    CHECK(pid.integral == 0.0);                     /* it never wound up */
    double u = pu_pid_step(&pid, &c, -0.5, NAN, 0, 0.1);
    CHECK(u < 0.0);                                 /* leaves the limit at once */
    CHECK_NEAR(u, -0.5 - 0.5 * 0.5 * 0.1, 1e-12);
    /* Without the rule the integral would hold 0.5 * 5 * 60 = 150 and the
     * output would stay at +1 for minutes. Integration that pulls the
     * output back from a limit still runs: */
    pu_pid_reset(&pid);
    pid.integral = 0.9;
    u = pu_pid_step(&pid, &c, 2.0, NAN, 0, 0.1);    /* saturated high, error positive: hold */
    CHECK(u == 1.0 && pid.integral == 0.9);
    u = pu_pid_step(&pid, &c, -0.05, NAN, 0, 0.1);  /* error negative: integrates down */
    CHECK_NEAR(pid.integral, 0.9 - 0.5 * 0.05 * 0.1, 1e-12);
    /* the integrator's own bound */
    pu_pid_config bounded = {.kp = 0, .ki = 1, .out_min = -10, .out_max = 10, .i_limit = 0.2};
    pu_pid_reset(&pid);
    for (int i = 0; i < 100; i++)
        u = pu_pid_step(&pid, &bounded, 1.0, NAN, 0, 0.1);
    CHECK_NEAR(u, 0.2, 1e-12);
}

void lib_pid_slew_limit(void)
{
    pu_pid_config c = {.kp = 100, .out_min = -1, .out_max = 1, .rate_max = 0.5};
    pu_pid pid;
    pu_pid_reset(&pid);
    pu_pid_preset_output(&pid, -1.0);               /* where the actuator is now */
    CHECK(pu_pid_step(&pid, &c, 1.0, NAN, 0, 0.0) == -1.0); /* first cycle, no time: holds */
    double prev = -1.0;
    int steps = 0;
    while (prev < 1.0 && steps < 1000) {
        double u = pu_pid_step(&pid, &c, 1.0, NAN, 0, 0.1);
        CHECK(u - prev <= 0.05 + 1e-12);
        prev = u;
        steps++;
    }
    CHECK(steps == 40);                             /* 2 / (0.5 * 0.1) */
    /* while slew-limited the integrator does not run either */
    pu_pid_config ci = {.kp = 1, .ki = 1, .out_min = -10, .out_max = 10, .rate_max = 0.1};
    pu_pid_reset(&pid);
    pu_pid_preset_output(&pid, 0.0);
    for (int i = 0; i < 10; i++)
        pu_pid_step(&pid, &ci, 5.0, NAN, 0, 0.1);
    CHECK(pid.limited && pid.integral == 0.0);
}

void lib_pid_integral_zone(void)
{
    pu_pid_config c = {.kp = 0, .ki = 1, .out_min = -10, .out_max = 10, .i_zone = 0.5};
    pu_pid pid;
    pu_pid_reset(&pid);
    pu_pid_step(&pid, &c, 2.0, NAN, 0, 1.0);
    CHECK(pid.integral == 0.0);                     /* outside the zone */
    pu_pid_step(&pid, &c, 0.4, NAN, 0, 1.0);
    CHECK_NEAR(pid.integral, 0.4, 1e-12);
}

void lib_pid_bad_input(void)
{
    pu_pid_config c = {.kp = 1, .ki = 1, .out_min = -1, .out_max = 1};
    pu_pid pid;
    pu_pid_reset(&pid);
    CHECK(pu_pid_step(&pid, &c, NAN, NAN, 0, 0.1) == 0.0);  /* nothing yet: 0 */
    double u = pu_pid_step(&pid, &c, 0.3, NAN, 0, 0.1);
    double i = pid.integral;
    CHECK(pu_pid_step(&pid, &c, NAN, NAN, 0, 0.1) == u);    /* holds */
    CHECK(pu_pid_step(&pid, &c, 0.3, NAN, INFINITY, 0.1) == u);
    CHECK(pid.integral == i);                                /* untouched */
    CHECK(isfinite(pu_pid_step(&pid, &c, 0.3, INFINITY, 0, 0.1)));
}

void lib_pid_config_check(void)
{
    char err[128];
    pu_pid_config ok = {.kp = 1, .out_min = -1, .out_max = 1};
    CHECK(pu_pid_config_check(&ok, err, sizeof err) == 0);
    pu_pid_config reversed = {.kp = 1, .out_min = 1, .out_max = -1};
    CHECK(pu_pid_config_check(&reversed, err, sizeof err) == -1);
    CHECK_HAS(err, "output limits are reversed");
    pu_pid_config negative = {.ki = -1, .out_min = -1, .out_max = 1};
    CHECK(pu_pid_config_check(&negative, err, sizeof err) == -1);
    CHECK_HAS(err, "must not be negative");
    pu_pid_config nan = {.kp = NAN};
    CHECK(pu_pid_config_check(&nan, err, sizeof err) == -1);
}
