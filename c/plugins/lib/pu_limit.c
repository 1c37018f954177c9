#include "plugins/lib/pu_limit.h"

#include <math.h>

double pu_clamp(double x, double lo, double hi)
{
    if (!(x >= lo)) /* also NaN */
        return lo;
    return x > hi ? hi : x;
}

double pu_clamp_sym(double x, double lim) { return pu_clamp(x, -lim, lim); }

double pu_rate_limit(double prev, double target, double max_rate, double dt)
{
    if (max_rate <= 0.0)
        return target;
    if (!(dt > 0.0))
        return prev;
    double step = max_rate * dt;
    return pu_clamp(target, prev - step, prev + step);
}

void pu_lowpass_reset(pu_lowpass *f)
{
    f->y = 0.0;
    f->primed = 0;
}

double pu_lowpass_step(pu_lowpass *f, double x, double tau, double dt)
{
    if (!f->primed || tau <= 0.0) {
        f->y = x;
        f->primed = 1;
        return x;
    }
    if (dt > 0.0)
        f->y += (1.0 - exp(-dt / tau)) * (x - f->y);
    return f->y;
}
