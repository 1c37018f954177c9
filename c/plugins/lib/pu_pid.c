#include "plugins/lib/pu_pid.h"

#include <math.h>
#include <stdio.h>

#include "plugins/lib/pu_limit.h"

void pu_pid_reset(pu_pid *p)
{
    p->integral = 0.0;
    p->prev_error = 0.0;
    p->output = 0.0;
    p->has_prev_error = 0;
    p->has_output = 0;
    p->limited = 0;
}

void pu_pid_preset_output(pu_pid *p, double output)
{
    if (isfinite(output)) {
        p->output = output;
        p->has_output = 1;
    }
}

double pu_pid_step(pu_pid *p, const pu_pid_config *c, double error, double derivative, double feedforward,
                   double dt)
{
    if (!isfinite(error) || !isfinite(feedforward)) {
        if (!p->has_output) {
            p->output = pu_clamp(0.0, c->out_min, c->out_max);
            p->has_output = 1;
        }
        return p->output;
    }
    if (dt < 0.0 || !isfinite(dt))
        dt = 0.0;
    double de = derivative;
    if (isnan(de))
        de = p->has_prev_error && dt > 0.0 ? (error - p->prev_error) / dt : 0.0;
    if (!isfinite(de))
        de = 0.0;

    double ilim = c->i_limit > 0.0 ? c->i_limit : fmax(fabs(c->out_min), fabs(c->out_max));
    double step_i = c->i_zone > 0.0 && fabs(error) > c->i_zone ? 0.0 : c->ki * error * dt;
    double i_new = pu_clamp_sym(p->integral + step_i, ilim);
    double unlimited = feedforward + c->kp * error + i_new + c->kd * de;
    double u = pu_clamp(unlimited, c->out_min, c->out_max);
    if (p->has_output)
        u = pu_rate_limit(p->output, u, c->rate_max, dt);

    /* Conditional integration: keep the old integral if this step's
     * integration pushes further into the limit the output is held at. */
    const double eps = 1e-12 * (1.0 + fabs(unlimited));
    p->limited = fabs(u - unlimited) > eps;
    if (p->limited && ((unlimited > u && step_i > 0.0) || (unlimited < u && step_i < 0.0)))
        i_new = p->integral;
    p->integral = i_new;
    p->prev_error = error;
    p->has_prev_error = 1;
    p->output = u;
    p->has_output = 1;
    return u;
}

int pu_pid_config_check(const pu_pid_config *c, char *err, size_t errlen)
{
    const double v[] = {c->kp, c->ki, c->kd, c->out_min, c->out_max, c->rate_max, c->i_limit, c->i_zone};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        if (!isfinite(v[i])) {
            snprintf(err, errlen, "PID settings must be finite numbers");
            return -1;
        }
    if (c->out_min > c->out_max) {
        snprintf(err, errlen, "output limits are reversed: min %g > max %g", c->out_min, c->out_max);
        return -1;
    }
    if (c->ki < 0.0) {
        snprintf(err, errlen, "integral gain must not be negative (%g)", c->ki);
        return -1;
    }
    return 0;
}
