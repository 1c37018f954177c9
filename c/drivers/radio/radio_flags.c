/* auv-radio's own flags (docs/radio.md), besides the framework's. */
#include <stdio.h>
#include <stdlib.h>

#include "drivers/radio/radio.h"

/* The end manager's status channel: its name is a flag, so the
 * subscription's suffix is set here before the framework subscribes. */
char radio_chasm_suffix[80] = "CHASM.NAVIGATOR";

static int number(const char *v, double lo, double hi, double *out, char *err, size_t errlen, const char *what)
{
    char *end;
    double x = strtod(v, &end);
    if (end == v || *end || !(x >= lo && x <= hi)) {
        snprintf(err, errlen, "%s: '%s' is not a number in [%g, %g]", what, v, lo, hi);
        return -1;
    }
    *out = x;
    return 0;
}

static int set_spool(void *st, const char *v, char *err, size_t errlen)
{
    (void)err, (void)errlen;
    ((radio_state *)st)->spool = v;
    return 0;
}

static int set_team_index(void *st, const char *v, char *err, size_t errlen)
{
    double x;
    if (number(v, -1, 15, &x, err, errlen, "--team-index") < 0 || x != (int)x)
        return -1;
    ((radio_state *)st)->team_index = (int)x;
    ((radio_state *)st)->given |= RADIO_GIVEN_TEAM;
    return 0;
}

static int set_end_manager(void *st, const char *v, char *err, size_t errlen)
{
    (void)st;
    if (snprintf(radio_chasm_suffix, sizeof radio_chasm_suffix, "CHASM.%s", v) >= (int)sizeof radio_chasm_suffix) {
        snprintf(err, errlen, "--end-manager: too long");
        return -1;
    }
    return 0;
}

static int set_surface(void *st, const char *v, char *err, size_t errlen)
{
    ((radio_state *)st)->given |= RADIO_GIVEN_SURFACE;
    return number(v, -100, 100, &((radio_state *)st)->surface_depth_m, err, errlen, "--surface-depth-m");
}

static int set_report(void *st, const char *v, char *err, size_t errlen)
{
    ((radio_state *)st)->given |= RADIO_GIVEN_REPORT;
    return number(v, 0.01, 86400, &((radio_state *)st)->report_period_s, err, errlen, "--report-period-s");
}

static int set_expiry(void *st, const char *v, char *err, size_t errlen)
{
    ((radio_state *)st)->given |= RADIO_GIVEN_EXPIRY;
    return number(v, 0, 1e9, &((radio_state *)st)->idle_expiry_s, err, errlen, "--idle-expiry-s");
}

static int set_peers(void *st, const char *v, char *err, size_t errlen)
{
    return radio_peers_parse(st, v, err, errlen);
}

static int set_key_file(void *st, const char *v, char *err, size_t errlen)
{
    (void)err, (void)errlen;
    ((radio_state *)st)->key_file = v;
    return 0;
}

const drv_flag radio_flags[] = {
    {"--spool", "DIR", "folder of the partial transfers (not a manager's plugin dir); required", set_spool},
    {"--team-index", "N", "this vehicle's team index for acoustic commands (default -1: none)", set_team_index},
    {"--end-manager", "NAME", "the manager whose state is reported home (default NAVIGATOR)", set_end_manager},
    {"--surface-depth-m", "M", "at the surface above this navigation depth (default 0.5)", set_surface},
    {"--report-period-s", "S", "the status home's period at the surface (default 2)", set_report},
    {"--idle-expiry-s", "S", "drop a partial transfer idle this long (default 3600)", set_expiry},
    {"--peers", "ID,ID", "teammates the status also goes to; theirs is published on <V>.PEER_RADIO_REPORT", set_peers},
    {"--key-file", "PATH", "team keys: acoustic commands checked, the commands issued signed", set_key_file},
    {0},
};
