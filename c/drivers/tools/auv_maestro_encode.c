/* auv-maestro-encode: the bytes the fins-and-thruster driver would write to its
 * Maestro, for commands read from stdin; no port, no LCM. A dry run of a
 * channel table, and the C half of the round trip with the simulator's
 * emulator (tests/drivers/test_maestro_emulator.py).
 *
 *   auv-maestro-encode TABLE < commands > bytes
 *
 * It writes each channel's speed and acceleration limits first, then per
 * input line:
 *
 *   cmd NOW UTIME RUDDER_RAD STERN_PLANE_RAD PROP_RPM   an actuators_t received at NOW [us]
 *   tick NOW                                           a turn of the loop: the watchdog
 *
 * and reports refusals and the watchdog on stderr, as the driver will. */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "drivers/servo/actuator_map.h"

static void put(const uint8_t *b, size_t n) { fwrite(b, 1, n, stdout); }

int main(int argc, char **argv)
{
    if (argc != 2 || !strcmp(argv[1], "--help")) {
        fputs("usage: auv-maestro-encode TABLE < commands > bytes\n"
              "  commands: 'cmd NOW UTIME RUDDER_RAD STERN_PLANE_RAD PROP_RPM' or 'tick NOW' per line\n",
              argc == 2 ? stdout : stderr);
        return argc == 2 ? 0 : 2;
    }
    static am_config cfg;
    char err[512];
    if (am_config_load(&cfg, argv[1], err, sizeof err)) {
        fprintf(stderr, "auv-maestro-encode: %s\n", err);
        return 2;
    }
    am_state st;
    am_state_init(&st);
    uint8_t out[AM_MAX_OUT];
    uint16_t targets[MAESTRO_MAX_CHANNELS];
    put(out, am_encode_limits(&cfg, out));
    char line[512];
    for (unsigned ln = 1; fgets(line, sizeof line, stdin); ln++) {
        long long now, utime;
        am_command c;
        if (sscanf(line, "cmd %lld %lld %lf %lf %lf", &now, &utime, &c.rudder_rad, &c.stern_plane_rad, &c.prop_rpm) ==
            5) {
            c.utime = utime;
            am_verdict v = am_apply(&cfg, &st, &c, now, targets);
            if (v != AM_OK)
                fprintf(stderr, "stdin:%u: command refused (%s)\n", ln, am_verdict_name(v));
            else
                put(out, am_encode_targets(&cfg, targets, out));
            if (v == AM_OK && st.resumed)
                fprintf(stderr, "stdin:%u: commands again: resumed\n", ln);
        } else if (sscanf(line, "tick %lld", &now) == 1) {
            am_watchdog_event e = am_watchdog(&cfg, &st, now, targets);
            if (e != AM_WD_QUIET) {
                fprintf(stderr, "stdin:%u: watchdog: %s\n", ln, am_watchdog_name(e));
                put(out, am_encode_targets(&cfg, targets, out));
            }
        } else {
            fprintf(stderr, "stdin:%u:1: expected 'cmd NOW UTIME RUDDER STERN RPM' or 'tick NOW'\n", ln);
            return 2;
        }
    }
    fprintf(stderr, "applied %" PRIu64 ", clamped %" PRIu64 ", watchdog trips %" PRIu64 "\n", st.applied, st.clamped,
            st.watchdog_trips);
    return 0;
}
