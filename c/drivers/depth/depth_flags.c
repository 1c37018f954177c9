/* auv-depth's own flags: the depth model, the sensor's unit and address, and
 * the polling. Each range is what a vehicle's sensor can mean; beyond it is a
 * typo, refused at start rather than a wrong depth at sea. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "drivers/depth/depth.h"

static int in_range(const char *v, double lo, double hi, double *out)
{
    char *end;
    double d = strtod(v, &end);
    if (end == v || *end || !isfinite(d) || d < lo || d > hi)
        return -1;
    *out = d;
    return 0;
}

static int int_in_range(const char *v, long lo, long hi, int *out)
{
    char *end;
    long l = strtol(v, &end, 10);
    if (end == v || *end || l < lo || l > hi)
        return -1;
    *out = (int)l;
    return 0;
}

#define SETTER(fn, bit, expr_ok, msg)                                \
    int fn(void *state, const char *v, char *err, size_t n)          \
    {                                                                \
        depth_state *s = state;                                      \
        if (!(expr_ok)) {                                            \
            snprintf(err, n, msg ", not '%s'", v);                   \
            return -1;                                               \
        }                                                            \
        s->settings_done |= (bit);                                   \
        return 0;                                                    \
    }

/* fresh water 1000, brines 1200: anything else is not water */
SETTER(depth_set_rho, 1, in_range(v, 900.0, 1300.0, &s->model.rho_kgpm3) == 0,
       "--rho wants a density in kg/m^3 in [900, 1300]")
SETTER(depth_set_g, 2, in_range(v, 9.7, 9.9, &s->model.g_mps2) == 0, "--g wants m/s^2 in [9.7, 9.9]")
/* the surface's atmosphere: from a deep low to a strong high, with margin */
SETTER(depth_set_p_atm, 4, in_range(v, 80000.0, 110000.0, &s->model.p_atm_pa) == 0,
       "--p-atm wants pascals in [80000, 110000]")
SETTER(depth_set_units, 8, int_in_range(v, DQ_PSI, DQ_MH2O, &s->unit) == 0,
       "--units wants the sensor's UN code 1..8 (1 psi, 2 hPa, 3 bar, 4 kPa, 5 MPa, 6 inHg, 7 mmHg, 8 mH2O)")
/* address 00 is the host's own */
SETTER(depth_set_address, 16, int_in_range(v, 1, 99, &s->address) == 0, "--address wants 1..99")
/* the framework ticks every 100 ms at least: faster polls would only jitter */
SETTER(depth_set_rate, 32, in_range(v, 0.1, 10.0, &s->rate_hz) == 0, "--rate wants Hz in [0.1, 10]")
SETTER(depth_set_temp_every, 64, int_in_range(v, 0, 100000, &s->temp_every) == 0,
       "--temp-every wants a count of polls 0..100000 (0: no temperature)")
SETTER(depth_set_timeout, 128, in_range(v, 0.05, 10.0, &s->timeout_s) == 0,
       "--timeout wants seconds in [0.05, 10]")
