/* Fuzz entry point for auv-frontseat with Bluefin's payload interface (c/frontseat/bluefin.c): any
 * bytes from the frontseat, in reads cut by the input itself, with setpoints
 * made of the input's bytes (any doubles, NaN and infinities included) between
 * them. Every NAV it publishes must decode and hold a position on the earth, a
 * depth and a heading in range; every request it writes must be one $BPRMB
 * inside the limits it was given: nothing the frontseat or the navigator says
 * may put a value outside them on the wire (libFuzzer, or the project's driver
 * c/chasm/fuzz/fuzz_driver.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_frontseat_status_t.h"
#include "auv/auv_nav_solution_t.h"
#include "common/lcm_rx.h"
#include "drivers/fuzz/fuzz_frontseat.h"
#include "frontseat/frontseat.h"

#define MAX_DEPTH 40.0
#define MAX_SPEED 2.0

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz_bluefin: broken: %s\n", what);
        abort();
    }
}

static void sink(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    (void)user;
    if (!strcmp(channel, "FUZZ.NAV")) {
        auv_nav_solution_t m;
        check(rx_decode(type, data, len, &m) == 0, "a NAV decodes");
        check(fabs(m.latitude_deg) <= 90.0 && fabs(m.longitude_deg) <= 180.0, "a position on the earth");
        check(isfinite(m.depth_m) && m.depth_m >= -10.0 && m.depth_m <= 6000.0, "a depth in range");
        check(m.heading_rad >= 0.0 && m.heading_rad < 2.0 * M_PI, "a heading in [0, 2pi)");
        check(m.altitude_m == -1.0 || (m.altitude_m >= 0.0 && m.altitude_m <= 1000.0), "an altitude");
        check(isnan(m.u_mps) || (m.u_mps >= 0.0 && m.u_mps <= 10.0), "a speed in range");
        auv_nav_solution_t_decode_cleanup(&m);
    } else {
        check(!strcmp(channel, "FUZZ.FRONTSEAT"), "only NAV and FRONTSEAT");
        auv_frontseat_status_t m;
        check(rx_decode(type, data, len, &m) == 0, "a status decodes");
        check(m.state >= 0 && m.state <= 5, "a state");
        check(!m.has_control || m.state == AUV_FRONTSEAT_STATUS_T_STATE_PAYLOAD, "control only in payload state");
        auv_frontseat_status_t_decode_cleanup(&m);
    }
}

/* Every byte written must be one whole $BPLOG, $BPSTS or $BPRMB sentence, the
 * RMB's numbers inside the limits. */
static int on_write(void *user, const uint8_t *data, size_t n)
{
    (void)user;
    char buf[256];
    check(n < sizeof buf, "a sentence of sane length");
    memcpy(buf, data, n);
    buf[n] = '\0';
    check(n > 5 && buf[n - 2] == '\r' && buf[n - 1] == '\n', "CR LF");
    if (!strncmp(buf, "$BPLOG,", 7) || !strncmp(buf, "$BPSTS,", 7))
        return 0;
    double h, d, v;
    int hh, mm, ss, ms, dm, sm, hm;
    check(!strncmp(buf, "$BPRMB,", 7), "a $BPRMB");
    /* its time: hhmmss.sss, or seconds since 1970 with three decimals (as the vehicle writes its own) */
    const char *t = buf + 7, *comma = strchr(t, ',');
    check(comma != NULL, "a $BPRMB");
    size_t int_digits = strspn(t, "0123456789");
    check(t[int_digits] == '.' && strspn(t + int_digits + 1, "0123456789") == 3 && t + int_digits + 4 == comma,
          "a time of three decimals");
    if (int_digits == 6) {
        check(sscanf(t, "%2d%2d%2d.%3d", &hh, &mm, &ss, &ms) == 4, "a time of day");
        check(hh < 24 && mm < 60 && ss < 60 && ms < 1000, "a time of day");
    } else {
        check(int_digits >= 9 && int_digits <= 11, "seconds since 1970");
    }
    if (!strncmp(comma, ",0,0,2,0,0,1*", 13))
        return 0; /* a stop */
    check(sscanf(comma, ",%lf,%lf,%d,%lf,%d,%d*", &h, &d, &dm, &v, &sm, &hm) == 6, "a $BPRMB");
    check(h >= 0.0 && h < 360.05, "a heading in [0, 360)");
    check(d >= 0.0 && d <= MAX_DEPTH + 0.05, "a depth inside the limit");
    check(v >= 0.0 && v <= MAX_SPEED + 0.005, "a speed inside the limit");
    check(dm == 0 && sm == 1 && hm == 0, "a depth, a speed, a heading");
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_frontseat_one("fuzz_bluefin", "bluefin", sink, on_write, data, size);
}
