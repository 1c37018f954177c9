#include "drivers/common/nmea.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *nmea_result_name(nmea_result r)
{
    static const char *const names[NMEA_RESULT_COUNT] = {
        [NMEA_OK] = "ok",
        [NMEA_BAD_CHECKSUM] = "bad checksum",
        [NMEA_NO_CHECKSUM] = "no checksum",
        [NMEA_TOO_LONG] = "line too long",
        [NMEA_BAD_CHAR] = "bad character",
        [NMEA_TRUNCATED] = "truncated sentence",
        [NMEA_BAD_ADDRESS] = "bad address field",
        [NMEA_TOO_MANY_FIELDS] = "too many fields",
    };
    return (unsigned)r < NMEA_RESULT_COUNT ? names[r] : "unknown";
}

void nmea_framer_init(nmea_framer *f, int allow_no_checksum)
{
    memset(f, 0, sizeof *f);
    f->allow_no_checksum = allow_no_checksum;
}

uint8_t nmea_checksum(const char *body, size_t len)
{
    uint8_t x = 0;
    for (size_t i = 0; i < len; i++)
        x ^= (uint8_t)body[i];
    return x;
}

int nmea_format(char *out, size_t n, const char *body)
{
    size_t len = strlen(body);
    int w = snprintf(out, n, "$%s*%02X\r\n", body, nmea_checksum(body, len));
    return w < 0 || (size_t)w >= n ? -1 : w;
}

static int hexval(int c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return -1;
}

/* The address field: 2-letter talker + 3-letter type (GPGGA), or a
 * proprietary one: 'P', the maker's three-letter code and what the maker
 * puts after it. NMEA 0183 leaves a proprietary sentence's content to its
 * maker, and makers use it freely: SiRF's "$PSRFTXTVersion GSW3.2.2*78" has
 * no comma and a space. So a proprietary address is any printable text (its
 * type keeps the leading letters and digits, up to 15); a standard one is
 * exactly 5 capitals or digits. */
static nmea_result split_address(const char *addr, nmea_sentence *out)
{
    size_t n = strlen(addr);
    if (n >= 2 && addr[0] == 'P' && isupper((unsigned char)addr[1])) {
        size_t k = 0;
        while (k < n && k + 1 < sizeof out->type && isalnum((unsigned char)addr[k]))
            k++;
        out->talker[0] = '\0';
        memcpy(out->type, addr, k);
        out->type[k] = '\0';
        return NMEA_OK;
    }
    if (n != 5)
        return NMEA_BAD_ADDRESS;
    for (size_t i = 0; i < n; i++)
        if (!isupper((unsigned char)addr[i]) && !isdigit((unsigned char)addr[i]))
            return NMEA_BAD_ADDRESS;
    memcpy(out->talker, addr, 2);
    out->talker[2] = '\0';
    memcpy(out->type, addr + 2, 4);
    return NMEA_OK;
}

nmea_result nmea_parse_line(const char *line, size_t len, int allow_no_checksum, nmea_sentence *out)
{
    while (len > 0 && (line[len - 1] == '\r' || line[len - 1] == '\n'))
        len--;
    if (len < 1 || (line[0] != '$' && line[0] != '!'))
        return NMEA_BAD_ADDRESS;
    if (len > NMEA_MAX_SENTENCE)
        return NMEA_TOO_LONG;
    for (size_t i = 0; i < len; i++)
        if (line[i] < 0x20 || line[i] > 0x7e)
            return NMEA_BAD_CHAR;
    memcpy(out->text, line, len);
    out->text[len] = '\0';
    /* the checksum: the last '*' followed by two hex digits ends the data */
    size_t end = len;
    const char *star = memchr(line, '*', len);
    if (star) {
        size_t at = (size_t)(star - line);
        if (at + 3 != len)
            return NMEA_BAD_CHECKSUM; /* '*' inside the data, or not two digits after it */
        int hi = hexval(line[at + 1]), lo = hexval(line[at + 2]);
        if (hi < 0 || lo < 0 || (uint8_t)(hi * 16 + lo) != nmea_checksum(line + 1, at - 1))
            return NMEA_BAD_CHECKSUM;
        end = at;
    } else if (!allow_no_checksum) {
        return NMEA_NO_CHECKSUM;
    }
    out->checksummed = star != NULL;
    size_t body = end - 1; /* without the '$' */
    memcpy(out->storage, line + 1, body);
    out->storage[body] = '\0';
    /* split on commas; the first field is the address */
    char *p = out->storage, *comma = strchr(p, ',');
    if (comma)
        *comma = '\0';
    nmea_result r = split_address(p, out);
    if (r != NMEA_OK)
        return r;
    out->nfields = 0;
    while (comma) {
        if (out->nfields == NMEA_MAX_FIELDS)
            return NMEA_TOO_MANY_FIELDS;
        p = comma + 1;
        comma = strchr(p, ',');
        if (comma)
            *comma = '\0';
        out->field[out->nfields++] = p;
    }
    return NMEA_OK;
}

/* The buffer holds a whole sentence: it ends with '*' and two hex digits. */
static int ends_with_checksum(const nmea_framer *f)
{
    return f->len >= 4 && f->buf[f->len - 3] == '*' && hexval(f->buf[f->len - 2]) >= 0 &&
           hexval(f->buf[f->len - 1]) >= 0;
}

int nmea_framer_push(nmea_framer *f, uint8_t c, nmea_sentence *out)
{
    if (c == '$' || c == '!') {
        int r = -1;
        if (f->in_sentence && !f->skipping)
            /* a sentence whose *hh is complete ends here even without its
             * CR LF (a receiver's full output buffer); else it was cut */
            r = ends_with_checksum(f) ? (int)nmea_parse_line(f->buf, f->len, f->allow_no_checksum, out)
                                      : NMEA_TRUNCATED;
        f->in_sentence = 1;
        f->skipping = 0;
        f->len = 0;
        f->buf[f->len++] = (char)c;
        return r;
    }
    if (!f->in_sentence) {
        if (c != '\r' && c != '\n')
            f->garbage_bytes++;
        return -1;
    }
    if (c == '\r' || c == '\n') {
        f->in_sentence = 0;
        if (f->skipping) {
            f->skipping = 0;
            return -1;
        }
        return nmea_parse_line(f->buf, f->len, f->allow_no_checksum, out);
    }
    if (f->skipping)
        return -1;
    if (c < 0x20 || c > 0x7e) {
        if (f->len <= 6 && !memchr(f->buf, ',', f->len)) {
            /* a '$' in binary (a u-blox's UBX frames between its sentences)
             * began no sentence: all of it is garbage, not a broken line */
            f->garbage_bytes += f->len + 1;
            f->in_sentence = 0;
            return -1;
        }
        f->skipping = 1; /* the rest of this line is not a sentence */
        return NMEA_BAD_CHAR;
    }
    if (f->len >= NMEA_MAX_SENTENCE) {
        f->skipping = 1;
        return NMEA_TOO_LONG;
    }
    f->buf[f->len++] = (char)c;
    return -1;
}

/* ------------------------------------------------------------------ fields */

static const char *field(const nmea_sentence *s, int i)
{
    return i >= 0 && i < s->nfields ? s->field[i] : "";
}

int nmea_field_double(const nmea_sentence *s, int i, double *out)
{
    const char *v = field(s, i);
    if (!*v)
        return 0;
    /* digits, one '.', a leading sign: no hex, no exponent, no inf/nan */
    const char *p = v + (*v == '-' || *v == '+');
    int digits = 0, dots = 0;
    for (; *p; p++) {
        if (isdigit((unsigned char)*p))
            digits++;
        else if (*p == '.' && !dots)
            dots++;
        else
            return -1;
    }
    if (!digits || digits > 30)
        return -1;
    errno = 0;
    double d = strtod(v, NULL);
    if (errno || !isfinite(d))
        return -1;
    *out = d;
    return 1;
}

int nmea_field_int(const nmea_sentence *s, int i, long *out)
{
    double d;
    int r = nmea_field_double(s, i, &d);
    if (r <= 0)
        return r;
    if (d != floor(d) || fabs(d) > 1e15)
        return -1;
    *out = (long)d;
    return 1;
}

/* ddmm.mmmm with `degree_digits` digits of degrees, and its hemisphere. */
static int angle(const nmea_sentence *s, int i, int degree_digits, double limit, char pos, char neg, double *deg)
{
    const char *v = field(s, i), *h = field(s, i + 1);
    if (!*v && !*h)
        return 0;
    const char *dot = strchr(v, '.');
    size_t int_digits = dot ? (size_t)(dot - v) : strlen(v);
    if (int_digits != (size_t)degree_digits + 2 || (h[0] != pos && h[0] != neg) || h[1])
        return -1;
    double raw;
    if (nmea_field_double(s, i, &raw) != 1 || raw < 0)
        return -1;
    double d = floor(raw / 100.0), minutes = raw - 100.0 * d;
    if (minutes >= 60.0)
        return -1;
    double value = d + minutes / 60.0;
    if (value > limit)
        return -1;
    *deg = h[0] == neg ? -value : value;
    return 1;
}

int nmea_field_latitude(const nmea_sentence *s, int i, double *deg) { return angle(s, i, 2, 90.0, 'N', 'S', deg); }
int nmea_field_longitude(const nmea_sentence *s, int i, double *deg) { return angle(s, i, 3, 180.0, 'E', 'W', deg); }

int nmea_field_time_of_day(const nmea_sentence *s, int i, double *seconds)
{
    const char *v = field(s, i);
    if (!*v)
        return 0;
    if (strlen(v) < 6)
        return -1;
    for (int k = 0; k < 6; k++)
        if (!isdigit((unsigned char)v[k]))
            return -1;
    double frac = 0.0;
    if (v[6]) {
        if (v[6] != '.')
            return -1;
        for (const char *p = v + 7; *p; p++)
            if (!isdigit((unsigned char)*p))
                return -1;
        frac = strtod(v + 6, NULL);
    }
    int hh = (v[0] - '0') * 10 + (v[1] - '0'), mm = (v[2] - '0') * 10 + (v[3] - '0'),
        ss = (v[4] - '0') * 10 + (v[5] - '0');
    if (hh > 23 || mm > 59 || ss > 60)
        return -1;
    *seconds = hh * 3600.0 + mm * 60.0 + ss + frac;
    return 1;
}

int64_t nmea_unix_day(int year, int month, int day)
{
    static const int mdays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (year < 1970 || year > 2199 || month < 1 || month > 12 || day < 1)
        return -1;
    int leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    if (day > mdays[month - 1] + (month == 2 && leap))
        return -1;
    /* days from civil (proleptic Gregorian), March-based year */
    int y = year - (month <= 2);
    int64_t era = y / 400;
    int64_t yoe = y - era * 400;
    int64_t doy = (153 * (month + (month > 2 ? -3 : 9)) + 2) / 5 + day - 1;
    int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

int nmea_field_date_ddmmyy(const nmea_sentence *s, int i, int64_t *unix_day)
{
    const char *v = field(s, i);
    if (!*v)
        return 0;
    if (strlen(v) != 6)
        return -1;
    for (int k = 0; k < 6; k++)
        if (!isdigit((unsigned char)v[k]))
            return -1;
    int dd = (v[0] - '0') * 10 + (v[1] - '0'), mo = (v[2] - '0') * 10 + (v[3] - '0'),
        yy = (v[4] - '0') * 10 + (v[5] - '0');
    int64_t day = nmea_unix_day(yy >= 80 ? 1900 + yy : 2000 + yy, mo, dd);
    if (day < 0)
        return -1;
    *unix_day = day;
    return 1;
}
