/* Fuzz entry point for auv-frontseat with the Iver3 protocol (c/frontseat): any
 * bytes from the frontseat, in reads cut by the input itself, with setpoints
 * made of the input's bytes (any doubles, NaN and infinities included) between
 * them. Every NAV it publishes must decode and hold a position on the earth, a
 * depth and a heading in range; every request it writes must be one $OMS
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
#define MAX_SPEED_KN (2.0 * 3600.0 / 1852.0)

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz_iver3: broken: %s\n", what);
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
        check(isfinite(m.depth_m) && m.depth_m > -10.0 && m.depth_m < 1006.0, "a depth in range");
        check(m.heading_rad >= 0.0 && m.heading_rad < 2.0 * M_PI, "a heading in [0, 2pi)");
        check(m.altitude_m == -1.0 || (m.altitude_m >= 0.0 && m.altitude_m <= 305.0), "an altitude");
        check(isnan(m.u_mps) || (m.u_mps >= 0.0 && m.u_mps <= 10.3), "a speed in range (NaN: none heard yet)");
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

/* Every byte written must be whole $OSD or $OMS sentences, the OMS's numbers
 * inside the limits. */
static int on_write(void *user, const uint8_t *data, size_t n)
{
    (void)user;
    char buf[256];
    check(n < sizeof buf, "a sentence of sane length");
    memcpy(buf, data, n);
    buf[n] = '\0';
    if (!strncmp(buf, "$OSD,", 5))
        return 0;
    double h, d, p, kn;
    int t;
    check(sscanf(buf, "$OMS,%lf,%lf,%lf,%lf,%d*", &h, &d, &p, &kn, &t) == 5, "an $OMS");
    check(h >= 0.0 && h < 360.05, "a heading in [0, 360)");
    check(d >= 0.0 && d <= MAX_DEPTH + 0.05, "a depth inside the limit");
    check(kn >= 0.0 && kn <= MAX_SPEED_KN + 0.05, "a speed inside the limit");
    check(p == 30.0 && t == 5, "the configured pitch and timeout");
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_frontseat_one("fuzz_iver3", "iver3", sink, on_write, data, size);
}
