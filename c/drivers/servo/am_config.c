/* The channel table's reader (actuator_map.h; the format is in docs/drivers.md,
 * "Fins and thruster"). Line by line, words separated by blanks, `#` to the
 * end of a line a comment; every refusal says file:line:col. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/servo/actuator_map.h"

#define AM_MAX_LINE 512
#define AM_MAX_WORDS 16
#define AM_MAX_FILE (64 * 1024) /* a table is a few lines: a larger file is a mistake */

typedef struct {
    const char *file;
    unsigned line;
    char *err;
    size_t errcap;
    char word[AM_MAX_WORDS][AM_MAX_LINE + 1];
    unsigned col[AM_MAX_WORDS];
    unsigned n;
} reader;

static int fail(reader *r, unsigned col, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail(reader *r, unsigned col, const char *fmt, ...)
{
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (r->errcap)
        snprintf(r->err, r->errcap, "%s:%u:%u: %s", r->file, r->line, col, msg);
    return -1;
}

/* Splits one line into words; refuses control bytes (a binary file, a stray NUL). */
static int split(reader *r, const char *s, size_t len)
{
    r->n = 0;
    size_t i = 0;
    while (i < len) {
        unsigned char ch = (unsigned char)s[i];
        if (ch == '#')
            break;
        if (ch == ' ' || ch == '\t' || ch == '\r') {
            i++;
            continue;
        }
        if (ch < 0x20 || ch >= 0x7F)
            return fail(r, (unsigned)i + 1, "a byte outside printable ASCII (0x%02x)", ch);
        if (r->n == AM_MAX_WORDS)
            return fail(r, (unsigned)i + 1, "too many words (at most %d)", AM_MAX_WORDS);
        size_t start = i;
        while (i < len && s[i] != ' ' && s[i] != '\t' && s[i] != '\r' && s[i] != '#' &&
               (unsigned char)s[i] >= 0x20 && (unsigned char)s[i] < 0x7F)
            i++;
        memcpy(r->word[r->n], s + start, i - start);
        r->word[r->n][i - start] = '\0';
        r->col[r->n++] = (unsigned)start + 1;
    }
    return 0;
}

/* A plain decimal number: digits, one point, an exponent; no hex, no inf or
 * nan, no locale (the Python reader, sim.devices.maestro, takes the same). */
static int decimal(const char *s)
{
    int digits = 0;
    s += *s == '+' || *s == '-';
    for (; *s >= '0' && *s <= '9'; s++)
        digits++;
    if (*s == '.')
        for (s++; *s >= '0' && *s <= '9'; s++)
            digits++;
    if (!digits)
        return 0;
    if (*s == 'e' || *s == 'E') {
        s++;
        s += *s == '+' || *s == '-';
        if (*s < '0' || *s > '9')
            return 0;
        while (*s >= '0' && *s <= '9')
            s++;
    }
    return *s == '\0';
}

/* Word k as a finite number within [lo, hi]. */
static int number(reader *r, unsigned k, double lo, double hi, const char *what, double *out)
{
    if (k >= r->n)
        return fail(r, r->col[r->n - 1], "%s: a number is missing after '%s'", what, r->word[r->n - 1]);
    char *end;
    errno = 0;
    double v = strtod(r->word[k], &end);
    if (!decimal(r->word[k]) || end == r->word[k] || *end || errno || !isfinite(v))
        return fail(r, r->col[k], "%s: '%s' is not a number", what, r->word[k]);
    if (v < lo || v > hi)
        return fail(r, r->col[k], "%s: %s is outside %g..%g", what, r->word[k], lo, hi);
    *out = v;
    return 0;
}

static int whole(reader *r, unsigned k, double hi, const char *what, unsigned *out)
{
    double v;
    if (number(r, k, 0, hi, what, &v))
        return -1;
    if (v != floor(v))
        return fail(r, r->col[k], "%s: %s is not a whole number", what, r->word[k]);
    *out = (unsigned)v;
    return 0;
}

#define MAX_PULSE_US (MAESTRO_MAX_TARGET / 4.0)

/* channel N ACTUATOR NEUTRAL US_PER_UNIT MIN MAX [reversed] [speed S] [accel A] */
static int channel_line(reader *r, am_config *cfg)
{
    if (cfg->n == MAESTRO_MAX_CHANNELS)
        return fail(r, r->col[0], "more than %d channels", MAESTRO_MAX_CHANNELS);
    am_channel c;
    memset(&c, 0, sizeof c);
    if (whole(r, 1, MAESTRO_MAX_CHANNELS - 1, "channel number", &c.channel))
        return -1;
    for (unsigned i = 0; i < cfg->n; i++)
        if (cfg->ch[i].channel == c.channel)
            return fail(r, r->col[1], "channel %u is already in the table", c.channel);
    if (r->n < 3)
        return fail(r, r->col[1], "the actuator is missing (rudder, stern_plane or prop)");
    int a;
    for (a = 0; a < AM_N_ACTUATORS && strcmp(r->word[2], am_actuator_name((am_actuator)a)); a++)
        ;
    if (a == AM_N_ACTUATORS)
        return fail(r, r->col[2], "unknown actuator '%s' (rudder, stern_plane or prop)", r->word[2]);
    c.actuator = (am_actuator)a;
    /* pulses from 1 us: 0 would switch the channel off, past 4095.75 us the protocol cannot say */
    if (number(r, 3, 1, MAX_PULSE_US, "neutral [us]", &c.neutral_us) ||
        number(r, 4, 0, 1e9, "microseconds per unit", &c.us_per_unit) ||
        number(r, 5, 1, MAX_PULSE_US, "min [us]", &c.min_us) || number(r, 6, 1, MAX_PULSE_US, "max [us]", &c.max_us))
        return -1;
    if (c.us_per_unit <= 0)
        return fail(r, r->col[4], "microseconds per unit must be above 0 (a reversed servo: 'reversed')");
    if (c.min_us >= c.max_us)
        return fail(r, r->col[5], "min %g us is not below max %g us", c.min_us, c.max_us);
    if (c.neutral_us < c.min_us || c.neutral_us > c.max_us)
        return fail(r, r->col[3], "neutral %g us is outside min..max (%g..%g us)", c.neutral_us, c.min_us, c.max_us);
    for (unsigned k = 7; k < r->n; k++) {
        if (!strcmp(r->word[k], "reversed") && !c.reversed) {
            c.reversed = 1;
        } else if (!strcmp(r->word[k], "speed")) {
            if (whole(r, ++k, MAESTRO_MAX_SPEED, "speed", &c.speed))
                return -1;
        } else if (!strcmp(r->word[k], "accel")) {
            if (whole(r, ++k, MAESTRO_MAX_ACCELERATION, "accel", &c.accel))
                return -1;
        } else {
            return fail(r, r->col[k], "unexpected '%s' (options: reversed, speed N, accel N)", r->word[k]);
        }
    }
    cfg->ch[cfg->n++] = c;
    return 0;
}

static int protocol_line(reader *r, am_config *cfg)
{
    if (r->n >= 2 && !strcmp(r->word[1], "compact") && r->n == 2) {
        cfg->framing.pololu = 0;
        return 0;
    }
    if (r->n >= 2 && !strcmp(r->word[1], "pololu")) {
        unsigned dev = MAESTRO_DEFAULT_DEVICE;
        if (r->n > 3)
            return fail(r, r->col[3], "unexpected '%s'", r->word[3]);
        if (r->n == 3 && whole(r, 2, 127, "device number", &dev))
            return -1;
        cfg->framing.pololu = 1;
        cfg->framing.device = (uint8_t)dev;
        return 0;
    }
    return fail(r, r->n >= 2 ? r->col[1] : r->col[0], "protocol: 'compact' or 'pololu [DEVICE]'");
}

int am_config_parse(am_config *cfg, const char *text, size_t len, const char *file, char *err, size_t errcap)
{
    reader r;
    memset(&r, 0, sizeof r);
    r.file = file;
    r.err = err;
    r.errcap = errcap;
    memset(cfg, 0, sizeof *cfg);
    cfg->watchdog_us = -1;
    int have_protocol = 0;
    size_t pos = 0;
    while (pos < len) {
        r.line++;
        const char *nl = memchr(text + pos, '\n', len - pos);
        size_t n = nl ? (size_t)(nl - (text + pos)) : len - pos;
        if (n > AM_MAX_LINE)
            return fail(&r, AM_MAX_LINE + 1, "line longer than %d characters", AM_MAX_LINE);
        if (split(&r, text + pos, n))
            return -1;
        pos += n + 1;
        if (!r.n)
            continue;
        if (!strcmp(r.word[0], "channel")) {
            if (channel_line(&r, cfg))
                return -1;
        } else if (!strcmp(r.word[0], "protocol")) {
            if (have_protocol)
                return fail(&r, r.col[0], "protocol is already set");
            if (protocol_line(&r, cfg))
                return -1;
            have_protocol = 1;
        } else if (!strcmp(r.word[0], "watchdog")) {
            double s;
            if (cfg->watchdog_us >= 0)
                return fail(&r, r.col[0], "watchdog is already set");
            if (number(&r, 1, 0.01, 3600, "watchdog [s]", &s))
                return -1;
            if (r.n > 2)
                return fail(&r, r.col[2], "unexpected '%s' (the watchdog's timeout is in seconds)", r.word[2]);
            cfg->watchdog_us = llround(s * 1e6);
        } else {
            return fail(&r, r.col[0], "unknown keyword '%s' (protocol, watchdog, channel)", r.word[0]);
        }
    }
    r.line = 1; /* what is missing is the whole file's */
    if (cfg->watchdog_us < 0)
        return fail(&r, 1, "no 'watchdog SECONDS' line: how long without commands before neutral?");
    if (!cfg->n)
        return fail(&r, 1, "no 'channel' line: the table is empty");
    return 0;
}

int am_config_load(am_config *cfg, const char *path, char *err, size_t errcap)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errcap, "%s: cannot open: %s", path, strerror(errno));
        return -1;
    }
    static char text[AM_MAX_FILE + 1];
    size_t n = fread(text, 1, sizeof text, f);
    int bad = ferror(f);
    fclose(f);
    if (bad || n > AM_MAX_FILE) {
        snprintf(err, errcap, "%s: %s", path, bad ? "read error" : "larger than 64 kB: not a channel table");
        return -1;
    }
    return am_config_parse(cfg, text, n, path, err, errcap);
}
