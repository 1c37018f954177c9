#include "drivers/pressure/digiquartz.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

double dq_pascals_per_unit(int unit)
{
    switch (unit) {
    case DQ_PSI: return 6894.757293168;
    case DQ_HPA: return 100.0;
    case DQ_BAR: return 1e5;
    case DQ_KPA: return 1e3;
    case DQ_MPA: return 1e6;
    case DQ_INHG: return 3386.389;   /* at 0 C */
    case DQ_MMHG: return 133.322387415;
    case DQ_MH2O: return 9806.65;    /* conventional, 4 C */
    default: return 0.0;
    }
}

const char *dq_result_name(dq_result r)
{
    static const char *const names[DQ_RESULT_COUNT] = {
        [DQ_OK] = "ok",
        [DQ_TOO_LONG] = "line too long",
        [DQ_BAD_CHAR] = "bad character",
        [DQ_NOT_AN_ANSWER] = "not an answer",
        [DQ_WRONG_ADDRESS] = "wrong address",
        [DQ_BAD_VALUE] = "malformed value",
        [DQ_VALUE_RANGE] = "value out of range",
        [DQ_OWN_COMMAND] = "own command",
    };
    return r >= 0 && r < DQ_RESULT_COUNT ? names[r] : "unknown";
}

int dq_format_command(char *out, size_t n, int sensor, int host, const char *command)
{
    if (sensor < 0 || sensor > 99 || host < 0 || host > 99)
        return -1;
    int w = snprintf(out, n, "*%02d%02d%s\r\n", sensor, host, command);
    return w < 0 || (size_t)w >= n ? -1 : w;
}

void dq_framer_init(dq_framer *f) { memset(f, 0, sizeof *f); }

static int two_digits(const char *p)
{
    return isdigit((unsigned char)p[0]) && isdigit((unsigned char)p[1]) ? (p[0] - '0') * 10 + (p[1] - '0') : -1;
}

static dq_result parse(const char *line, size_t len, int host, int sensor, dq_answer *out)
{
    if (len < 6 || line[0] != '*')
        return DQ_NOT_AN_ANSWER;
    int to = two_digits(line + 1), from = two_digits(line + 3);
    if (to < 0 || from < 0)
        return DQ_NOT_AN_ANSWER;
    if (to == sensor && from == host && len > 5 && isupper((unsigned char)line[5]))
        return DQ_OWN_COMMAND; /* "*0100P3" read back from the line */
    if (to != host || from != sensor)
        return DQ_WRONG_ADDRESS;
    /* a plain decimal: optional sign, digits, at most one '.', at most 20
     * characters; spaces around it and a unit word after it are allowed */
    const char *v = line + 5;
    size_t n = len - 5;
    while (n > 0 && *v == ' ')
        v++, n--;
    while (n > 0 && v[n - 1] == ' ')
        n--;
    size_t word = n;
    while (word > 0 && isalpha((unsigned char)v[word - 1]))
        word--;
    if (word < n && word > 0 && v[word - 1] == ' ' && n - word <= 8) { /* "14.7069 psia" */
        n = word;
        while (n > 0 && v[n - 1] == ' ')
            n--;
    }
    size_t digits = 0, dots = 0;
    for (size_t i = 0; i < n; i++) {
        char c = v[i];
        if (isdigit((unsigned char)c))
            digits++;
        else if (c == '.' && !dots)
            dots++;
        else if (!(i == 0 && (c == '-' || c == '+')))
            return DQ_BAD_VALUE;
    }
    if (!digits || n > 20)
        return DQ_BAD_VALUE;
    out->host = to, out->sensor = from;
    out->value = strtod(v, NULL);
    return DQ_OK;
}

int dq_framer_push(dq_framer *f, uint8_t c, int host, int sensor, dq_answer *out)
{
    if (c == '\r' || c == '\n') {
        int had = f->len > 0 && !f->skipping;
        size_t len = f->len;
        f->len = 0;
        f->skipping = 0;
        if (!had)
            return DQ_NO_ANSWER_YET;
        f->buf[len] = '\0';
        return parse(f->buf, len, host, sensor, out);
    }
    if (f->skipping)
        return DQ_NO_ANSWER_YET;
    if (f->len == 0 && c != '*') {
        f->garbage_bytes++;
        return DQ_NO_ANSWER_YET;
    }
    if (c < 0x20 || c > 0x7e) {
        f->skipping = 1;
        return DQ_BAD_CHAR;
    }
    if (f->len >= DQ_MAX_LINE) {
        f->skipping = 1;
        return DQ_TOO_LONG;
    }
    f->buf[f->len++] = (char)c;
    return DQ_NO_ANSWER_YET;
}

dq_result dq_pressure_pa(double value, int unit, double *pa)
{
    double k = dq_pascals_per_unit(unit);
    if (k <= 0.0 || !isfinite(value))
        return DQ_BAD_VALUE;
    double p = value * k;
    if (!(p >= 0.0 && p <= 2000e5)) /* 2000 bar: deeper than any ocean */
        return DQ_VALUE_RANGE;
    *pa = p;
    return DQ_OK;
}

double dq_depth_m(const dq_depth_model *m, double pa) { return (pa - m->p_atm_pa) / (m->rho_kgpm3 * m->g_mps2); }

dq_result dq_temperature_c(double value, double *c)
{
    if (!isfinite(value))
        return DQ_BAD_VALUE;
    if (!(value >= -10.0 && value <= 60.0))
        return DQ_VALUE_RANGE;
    *c = value;
    return DQ_OK;
}
