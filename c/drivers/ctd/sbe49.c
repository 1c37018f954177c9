#include "drivers/ctd/sbe49.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* What the instrument measures (its stated ranges, with a margin): a reading
 * outside is not water the sensor saw. */
#define T_MIN (-5.0)
#define T_MAX 45.0
#define C_MIN (-0.01)
#define C_MAX 9.0
#define P_MIN (-20.0)
#define P_MAX 11000.0

static int hex_value(const char *s, int k, long *out)
{
    long v = 0;
    for (int i = 0; i < k; i++) {
        int c = (unsigned char)s[i];
        int d = isdigit(c) ? c - '0' : (c >= 'A' && c <= 'F') ? c - 'A' + 10 : (c >= 'a' && c <= 'f') ? c - 'a' + 10 : -1;
        if (d < 0)
            return -1;
        v = v * 16 + d;
    }
    *out = v;
    return 0;
}

static int all_hex(const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isxdigit((unsigned char)s[i]))
            return 0;
    return 1;
}

/* The manual's numbers are plain decimals ("-1.2345"): strtod would also take
 * an exponent, hex ("0x1A") or "inf", which no SBE 49 writes. */
static int plain_decimal(const char *p, const char *end)
{
    int digits = 0, dots = 0;
    if (p < end && (*p == '-' || *p == '+'))
        p++;
    for (; p < end; p++) {
        if (isdigit((unsigned char)*p))
            digits++;
        else if (*p == '.' && !dots)
            dots++;
        else
            return 0;
    }
    return digits > 0;
}

/* Decimal fields "a, b, c": up to 6 numbers; -1 if one is not a number. */
static int decimal_fields(const char *s, size_t n, double *v, int cap)
{
    char buf[SBE49_MAX_LINE + 1];
    memcpy(buf, s, n);
    buf[n] = 0;
    int k = 0;
    char *p = buf;
    for (;;) {
        while (*p == ' ')
            p++;
        char *end;
        double x = strtod(p, &end);
        if (end == p || !isfinite(x) || k >= cap || !plain_decimal(p, end))
            return -1;
        v[k++] = x;
        p = end;
        while (*p == ' ')
            p++;
        if (!*p)
            return k;
        if (*p != ',')
            return -1;
        p++;
    }
}

static sbe49_kind ranged(sbe49_sample *out, const char **why)
{
    if (!(out->temperature_c >= T_MIN && out->temperature_c <= T_MAX) ||
        !(out->conductivity_s_per_m >= C_MIN && out->conductivity_s_per_m <= C_MAX) ||
        !(out->pressure_dbar >= P_MIN && out->pressure_dbar <= P_MAX)) {
        *why = "out of range";
        return SBE49_BAD;
    }
    return SBE49_DATA;
}

sbe49_kind sbe49_parse_line(const char *line, size_t n, sbe49_sample *out, const char **why)
{
    *why = NULL;
    if (n >= 2 && line[0] == 'S' && line[1] == '>') { /* the prompt, then maybe the echo of a command */
        line += 2;
        n -= 2;
    }
    while (n && (line[0] == ' ' || line[0] == '\r'))
        line++, n--;
    while (n && (line[n - 1] == ' ' || line[n - 1] == '\r'))
        n--;
    if (n == 0)
        return SBE49_NOT_DATA;
    if (n > SBE49_MAX_LINE) {
        *why = "line too long";
        return SBE49_BAD;
    }
    memset(out, 0, sizeof *out);
    out->salinity_psu = out->sound_speed_mps = NAN;
    if (all_hex(line, n)) {
        if (n == 22) { /* 4 more digits: the pressure temperature voltage of OutputFormat=0 */
            *why = "raw counts";
            return SBE49_BAD;
        }
        if (n != 18) { /* a scan cut short or run together with the next */
            *why = "bad length";
            return SBE49_BAD;
        }
        long t, c, p;
        hex_value(line, 6, &t);
        hex_value(line + 6, 6, &c);
        hex_value(line + 12, 6, &p);
        out->temperature_c = t / 100000.0 - 10.0;
        out->conductivity_s_per_m = c / 1000000.0 - 1.0;
        out->pressure_dbar = p / 1000.0 - 100.0;
        out->format = 1;
        return ranged(out, why);
    }
    if (isdigit((unsigned char)line[0]) || line[0] == '-' || line[0] == '.') {
        double v[6];
        int k = decimal_fields(line, n, v, 6);
        if (k < 0 || k < 3 || k > 5) {
            *why = k < 0 ? "bad number" : "bad field count";
            return SBE49_BAD;
        }
        /* OutputFormat=2 (raw, decimal): temperature A/D counts, a whole number in the
         * hundreds of thousands, then a frequency: no temperature a sea has */
        if (k == 4 && v[0] > 1000.0 && v[0] == floor(v[0])) {
            *why = "raw counts";
            return SBE49_BAD;
        }
        out->temperature_c = v[0];
        out->conductivity_s_per_m = v[1];
        out->pressure_dbar = v[2];
        if (k == 5) {
            out->salinity_psu = v[3];
            out->sound_speed_mps = v[4];
        } else if (k == 4) {
            if (v[3] > 1000.0)
                out->sound_speed_mps = v[3];
            else
                out->salinity_psu = v[3];
        }
        if ((!isnan(out->salinity_psu) && !(out->salinity_psu >= 0 && out->salinity_psu <= 45)) ||
            (!isnan(out->sound_speed_mps) && !(out->sound_speed_mps >= 1300 && out->sound_speed_mps <= 1800))) {
            *why = "out of range";
            return SBE49_BAD;
        }
        out->format = 3;
        return ranged(out, why);
    }
    return SBE49_NOT_DATA; /* text: the status (DS), a command's echo, <Executed/> */
}
