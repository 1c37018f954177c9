/* $PAUVT, the time link's one sentence (timesync.h): parsing and formatting,
 * pure (no LCM, no clock), shared by the driver, the tests and the fuzzer. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "drivers/timesync/timesync.h"

/* An integer of 1..19 digits, nothing else (no sign, no point, no exponent):
 * a sim time in microseconds. -1 if it is not one or overflows. */
static int parse_utime(const char *v, int64_t *out)
{
    size_t n = strlen(v);
    if (n == 0 || n > 19)
        return -1;
    int64_t t = 0;
    for (size_t i = 0; i < n; i++) {
        if (v[i] < '0' || v[i] > '9')
            return -1;
        if (__builtin_mul_overflow(t, 10, &t) || __builtin_add_overflow(t, v[i] - '0', &t))
            return -1;
    }
    *out = t;
    return 0;
}

const char *pauvt_decode(const nmea_sentence *s, pauvt_values *out, char *why, size_t whylen)
{
    if (s->talker[0] || strcmp(s->type, "PAUVT") != 0) {
        snprintf(why, whylen, "%.40s on the time link", s->text);
        return "unknown sentence";
    }
    if (s->nfields != 2) {
        snprintf(why, whylen, "%d fields, not 2 (time, warp): %.60s", s->nfields, s->text);
        return "malformed sentence";
    }
    if (parse_utime(s->field[0], &out->utime) < 0) {
        snprintf(why, whylen, "time '%.30s' is not an integer of microseconds", s->field[0]);
        return "malformed time";
    }
    if (!tp_utime_valid(out->utime)) {
        snprintf(why, whylen, "time %.30s us is past 2100", s->field[0]);
        return "time out of range";
    }
    if (nmea_field_double(s, 1, &out->warp) != 1) {
        snprintf(why, whylen, "warp '%.30s' is not a number", s->field[1]);
        return "malformed warp";
    }
    if (!(out->warp >= 0.0 && out->warp <= PAUVT_MAX_WARP)) {
        snprintf(why, whylen, "warp %.30s is outside 0 .. %g", s->field[1], PAUVT_MAX_WARP);
        return "warp out of range";
    }
    return NULL;
}

int pauvt_format(char *out, size_t n, int64_t utime, double warp)
{
    char body[80];
    snprintf(body, sizeof body, "PAUVT,%lld,%.6g", (long long)utime, warp);
    return nmea_format(out, n, body);
}
