/* pu_limit.h: clamps, slew-rate limits and a first-order filter for plugins
 * (c/plugins/lib, linked into every plugin). All functions are pure except
 * pu_lowpass_step, which updates its filter. */
#ifndef PU_LIMIT_H
#define PU_LIMIT_H

#include "plugins/lib/pu_visibility.h"

/* x limited to [lo, hi] (lo <= hi). NaN is returned as lo, so a bad input
 * never reaches an actuator as NaN. */
PU_HIDDEN double pu_clamp(double x, double lo, double hi);
/* x limited to [-lim, lim] (lim >= 0). */
PU_HIDDEN double pu_clamp_sym(double x, double lim);
/* From prev towards target by at most max_rate * dt: a slew-rate limit.
 * max_rate <= 0 means no limit. dt <= 0 holds prev (no time has passed). */
PU_HIDDEN double pu_rate_limit(double prev, double target, double max_rate, double dt);

/* First-order low-pass y' = (x - y) / tau, discretised exactly for any dt.
 * The first sample initialises it (no start-up transient from 0). */
typedef struct {
    double y;
    int primed;
} pu_lowpass;
PU_HIDDEN void pu_lowpass_reset(pu_lowpass *f);
/* Filters x over dt seconds with time constant tau (tau <= 0: no filtering). */
PU_HIDDEN double pu_lowpass_step(pu_lowpass *f, double x, double tau, double dt);

#endif
