/* The Micro-Modem's NMEA subset: parsers and formatters (mm_msg.h). Every
 * number is checked against the range the interface guide gives it, so a
 * bridge or an emulator above this never sees an address of 300 or a rate
 * of 9. */
#include "drivers/modem/mm_msg.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Index = rate (packet type). Rates 1-5 are PSK; 0 is FH-FSK. */
static const int frame_bytes[MM_MAX_RATE + 1] = {32, 64, 64, 256, 256, 256};
static const int frames[MM_MAX_RATE + 1] = {1, 3, 3, 2, 2, 8};

int mm_rate_frame_bytes(int rate) { return rate >= 0 && rate <= MM_MAX_RATE ? frame_bytes[rate] : -1; }
int mm_rate_frames(int rate) { return rate >= 0 && rate <= MM_MAX_RATE ? frames[rate] : -1; }

static const char *const names[MM_KIND_COUNT] = {
    "", "CCCFG", "CCCFQ", "CCCYC", "CCTXD", "CCMPC", "CACFG", "CACYC",
    "CADRQ", "CATXD", "CARXD", "CAACK", "CAERR", "CAREV", "CAXST", "CACST",
};

const char *mm_kind_name(mm_kind k) { return k > MM_NONE && k < MM_KIND_COUNT ? names[k] : ""; }

int mm_hex_decode(const char *hex, uint8_t *out, int max)
{
    size_t len = strlen(hex);
    if (len % 2)
        return -1;
    if (len / 2 > (size_t)max)
        return -1;
    for (size_t i = 0; i < len; i += 2) {
        int v = 0;
        for (int k = 0; k < 2; k++) {
            char c = hex[i + (size_t)k];
            int d = c >= '0' && c <= '9' ? c - '0' : c >= 'A' && c <= 'F' ? c - 'A' + 10 : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
            if (d < 0)
                return -1;
            v = v * 16 + d;
        }
        out[i / 2] = (uint8_t)v;
    }
    return (int)(len / 2);
}

/* ---- parsing. Each helper returns 0 or sets *why and returns -1. */

typedef struct {
    const nmea_sentence *s;
    const char *why;
} reader;

static int fail(reader *r, const char *why)
{
    if (!r->why)
        r->why = why;
    return -1;
}

/* A required integer field in [lo, hi]; empty is "missing fields", a
 * malformed or out-of-range value `bad`. */
static int int_field(reader *r, int i, long lo, long hi, const char *bad, int *out)
{
    long v;
    int k = nmea_field_int(r->s, i, &v);
    if (k == 0)
        return fail(r, "missing fields");
    if (k < 0 || v < lo || v > hi)
        return fail(r, bad);
    *out = (int)v;
    return 0;
}

static int address(reader *r, int i, int *out) { return int_field(r, i, 0, MM_MAX_ADDRESS, "bad address", out); }
static int flag(reader *r, int i, int *out) { return int_field(r, i, 0, 1, "bad flag", out); }

/* An optional number: empty leaves *out as it was. */
static int opt_double(reader *r, int i, double *out)
{
    double v;
    int k = nmea_field_double(r->s, i, &v);
    if (k < 0)
        return fail(r, "bad number");
    if (k > 0)
        *out = v;
    return 0;
}

/* An ISO 8601 date and time, YYYY-MM-DDTHH:MM:SS[.ffffff] (the time fields
 * of Micro-Modem 2 firmware), into seconds of the day; -1 if it is not one. */
static double iso_time_of_day(const char *v)
{
    static const char shape[] = "dddd-dd-ddTdd:dd:dd";
    size_t n = strlen(v);
    if (n < sizeof shape - 1)
        return -1;
    for (size_t i = 0; i < sizeof shape - 1; i++)
        if (shape[i] == 'd' ? !isdigit((unsigned char)v[i]) : v[i] != shape[i])
            return -1;
    if (v[19] && (v[19] != '.' || strspn(v + 20, "0123456789") != n - 20))
        return -1;
    int hh = (v[11] - '0') * 10 + (v[12] - '0'), mm = (v[14] - '0') * 10 + (v[15] - '0'),
        ss = (v[17] - '0') * 10 + (v[18] - '0');
    if (hh > 23 || mm > 59 || ss > 60)
        return -1;
    return hh * 3600.0 + mm * 60.0 + ss + (v[19] ? atof(v + 19) : 0.0);
}

/* The modem's time of a message: HHMMSS[.sss] (the interface guide), or the
 * ISO date and time of later firmware; empty is -1. */
static int time_field(reader *r, int i, double *out)
{
    *out = -1;
    int k = nmea_field_time_of_day(r->s, i, out);
    if (k < 0) {
        *out = iso_time_of_day(r->s->field[i]);
        if (*out < 0)
            return fail(r, "bad time");
    }
    return 0;
}

static int hex_field(reader *r, int i, mm_data *d)
{
    const char *h = r->s->field[i];
    size_t len = strlen(h);
    if (len % 2)
        return fail(r, "odd hex length");
    if (len / 2 > MM_MAX_FRAME_BYTES)
        return fail(r, "data longer than any frame");
    d->n = mm_hex_decode(h, d->data, MM_MAX_FRAME_BYTES);
    if (d->n < 0)
        return fail(r, "bad hex");
    return 0;
}

/* A parameter name: the interface guide's three capital letters (SRC, CST,
 * BR1, ALL), or Micro-Modem 2 firmware's hierarchical ones (xst.version,
 * pwramp.txlevel): a letter, then letters, digits, '.' and '_'. */
static int name_ok(const char *s)
{
    size_t n = strlen(s);
    if (n < 2 || n >= sizeof(((mm_cfg *)0)->name) || !isalpha((unsigned char)s[0]))
        return 0;
    for (size_t i = 0; i < n; i++)
        if (!isalnum((unsigned char)s[i]) && s[i] != '.' && s[i] != '_')
            return 0;
    return 1;
}

/* A value: printable characters that cannot end a field or a sentence. */
static int value_ok(const char *s)
{
    size_t n = strlen(s);
    if (n < 1 || n >= sizeof(((mm_cfg *)0)->value))
        return 0;
    return strpbrk(s, ",*$!") == NULL;
}

static int cfg(reader *r, mm_cfg *c, int with_value)
{
    const nmea_sentence *s = r->s;
    if (s->nfields < (with_value ? 2 : 1) || !s->field[0][0] || (with_value && !s->field[1][0]))
        return fail(r, "missing fields");
    if (!name_ok(s->field[0]))
        return fail(r, "bad name");
    snprintf(c->name, sizeof c->name, "%s", s->field[0]);
    c->value[0] = 0;
    if (with_value) {
        if (!value_ok(s->field[1]))
            return fail(r, "bad value");
        snprintf(c->value, sizeof c->value, "%s", s->field[1]);
    }
    return 0;
}

static int cyc(reader *r, mm_cyc *c)
{
    if (r->s->nfields < 6)
        return fail(r, "missing fields");
    if (int_field(r, 0, 0, 1000, "bad number", &c->cmd) || address(r, 1, &c->src) || address(r, 2, &c->dest) ||
        int_field(r, 3, 0, 1000, "unknown rate", &c->rate) || flag(r, 4, &c->ack))
        return -1;
    if (c->rate > MM_MAX_RATE)
        return fail(r, "unknown rate");
    return int_field(r, 5, 1, mm_rate_frames(c->rate), "bad frame count", &c->nframes);
}

static int data(reader *r, mm_data *d, mm_kind k)
{
    int nf = k == MM_CARXD ? 5 : 4;
    memset(d, 0, sizeof *d);
    if (r->s->nfields < nf)
        return fail(r, "missing fields");
    if (r->s->nfields > nf)
        return fail(r, "too many fields");
    if (address(r, 0, &d->src) || address(r, 1, &d->dest) || flag(r, 2, &d->ack))
        return -1;
    if (k == MM_CATXD)
        return int_field(r, 3, 0, MM_MAX_FRAME_BYTES, "data longer than any frame", &d->n);
    if (k == MM_CARXD && int_field(r, 3, 1, MM_MAX_FRAMES, "bad frame number", &d->frame))
        return -1;
    return hex_field(r, nf - 1, d);
}

static int drq(reader *r, mm_drq *d)
{
    if (r->s->nfields < 6)
        return fail(r, "missing fields");
    if (time_field(r, 0, &d->time_s) || address(r, 1, &d->src) || address(r, 2, &d->dest) || flag(r, 3, &d->ack))
        return -1;
    return int_field(r, 4, 0, MM_MAX_FRAME_BYTES, "data longer than any frame", &d->nbytes) ||
           int_field(r, 5, 1, MM_MAX_FRAMES, "bad frame number", &d->frame);
}

static int ack(reader *r, mm_ack *a)
{
    if (r->s->nfields < 3)
        return fail(r, "missing fields");
    a->ack = -1;
    if (address(r, 0, &a->src) || address(r, 1, &a->dest) || int_field(r, 2, 1, MM_MAX_FRAMES, "bad frame number", &a->frame))
        return -1;
    if (r->s->nfields > 3 && r->s->field[3][0] && flag(r, 3, &a->ack))
        return -1;
    return 0;
}

/* Text fields keep what fits; the rest of a long text is cut, not refused. */
static void copy_text(char *dst, size_t n, const char *src) { snprintf(dst, n, "%s", src); }

static int err(reader *r, mm_err *e)
{
    const nmea_sentence *s = r->s;
    if (s->nfields < 3)
        return fail(r, "missing fields");
    if (time_field(r, 0, &e->time_s))
        return -1;
    copy_text(e->module, sizeof e->module, s->field[1]);
    int text = 2;
    e->number = -1;
    if (s->nfields >= 4) { /* HHMMSS,MODULE,NUMBER,TEXT (a text with commas keeps them) */
        long v;
        int k = nmea_field_int(s, 2, &v);
        if (k < 0 || (k > 0 && (v < 0 || v > 100000)))
            return fail(r, "bad number");
        e->number = k > 0 ? (int)v : -1;
        text = 3;
    }
    size_t used = 0;
    e->text[0] = 0;
    for (int i = text; i < s->nfields && used + 1 < sizeof e->text; i++) {
        int w = snprintf(e->text + used, sizeof e->text - used, "%s%s", i > text ? "," : "", s->field[i]);
        used += w > 0 ? (size_t)w : 0;
    }
    if (used >= sizeof e->text)
        e->text[sizeof e->text - 1] = 0;
    return 0;
}

/* CAREV,HHMMSS,IDENT,VERSION; some firmware leaves the time out after a boot
 * (CAREV,INIT,VERSION): a first field that starts with a letter is the
 * identifier. */
static int rev(reader *r, mm_rev *v)
{
    const nmea_sentence *s = r->s;
    int o = s->nfields > 0 && isalpha((unsigned char)s->field[0][0]) ? 0 : 1;
    v->time_s = -1;
    if (s->nfields < 1 + o || !s->field[o][0])
        return fail(r, "missing fields");
    if (o && time_field(r, 0, &v->time_s))
        return -1;
    copy_text(v->ident, sizeof v->ident, s->field[o]);
    copy_text(v->version, sizeof v->version, s->nfields > o + 1 ? s->field[o + 1] : "");
    return 0;
}

/* Version 0 starts with a YYYYMMDD date; versions 6 and later with their
 * number, and keep version 6's fields where it put them (7 and 8, of Micro-
 * Modem 2 firmware, add theirs at the end). */
static int xst(reader *r, mm_xst *x)
{
    const nmea_sentence *s = r->s;
    long first;
    if (s->nfields < 15 || nmea_field_int(s, 0, &first) != 1)
        return fail(r, "missing fields");
    x->version = first > 19700000 ? 0 : (int)first;
    if (x->version != 0 && (x->version < 6 || x->version > MM_MAX_STAT_VERSION))
        return fail(r, "unknown version");
    int o = x->version ? 1 : 0;
    if (s->nfields < 15 + o)
        return fail(r, "missing fields");
    if (int_field(r, 7 + o, 0, 1000, "unknown rate", &x->rate) || address(r, 8 + o, &x->src) ||
        address(r, 9 + o, &x->dest) || flag(r, 10 + o, &x->ack) ||
        int_field(r, 11 + o, 0, MM_MAX_FRAMES, "bad frame count", &x->nframes_expected) ||
        int_field(r, 12 + o, 0, MM_MAX_FRAMES, "bad frame count", &x->nframes_sent) ||
        int_field(r, 13 + o, 0, 1000, "bad number", &x->packet_type) ||
        int_field(r, 14 + o, 0, MM_MAX_FRAMES * MM_MAX_FRAME_BYTES, "bad number", &x->nbytes))
        return -1;
    return x->rate > MM_MAX_RATE ? fail(r, "unknown rate") : 0;
}

static int cst(reader *r, mm_cst *c)
{
    const nmea_sentence *s = r->s;
    long first;
    if (s->nfields < 22 || nmea_field_int(s, 0, &first) != 1)
        return fail(r, "missing fields");
    c->version = first >= 6 ? (int)first : 0;
    if (c->version > MM_MAX_STAT_VERSION)
        return fail(r, "unknown version");
    int o = c->version ? 1 : 0;
    if (s->nfields < 22 + o)
        return fail(r, "missing fields");
    if (int_field(r, o, 0, 2, "bad number", &c->mode) || int_field(r, 12 + o, 0, 1000, "unknown rate", &c->rate) ||
        address(r, 13 + o, &c->src) || address(r, 14 + o, &c->dest) ||
        int_field(r, 16 + o, 0, 1000, "bad number", &c->packet_type) ||
        int_field(r, 17 + o, 0, MM_MAX_FRAMES, "bad frame count", &c->nframes) ||
        int_field(r, 18 + o, 0, MM_MAX_FRAMES, "bad frame count", &c->nbad))
        return -1;
    if (c->rate > MM_MAX_RATE)
        return fail(r, "unknown rate");
    /* the SNRs: NaN when the modem leaves them empty (or the sentence ends) */
    double nan = 0.0 / 0.0;
    c->snr_rss = c->snr_in = c->snr_out = c->snr_sym = c->mse = c->doppler = c->noise = nan;
    double *f[] = {&c->snr_rss, &c->snr_in, &c->snr_out, &c->snr_sym, &c->mse};
    for (int i = 0; i < 5; i++)
        if (opt_double(r, 19 + o + i, f[i]))
            return -1;
    if (opt_double(r, 25 + o, &c->doppler) || opt_double(r, 26 + o, &c->noise))
        return -1;
    return 0;
}

int mm_parse(const nmea_sentence *s, mm_msg *m, const char **why)
{
    memset(m, 0, sizeof *m);
    reader r = {s, NULL};
    char addr[sizeof s->talker + sizeof s->type];
    snprintf(addr, sizeof addr, "%s%s", s->talker, s->type);
    for (int k = MM_NONE + 1; k < MM_KIND_COUNT; k++)
        if (!strcmp(addr, names[k]))
            m->kind = (mm_kind)k;
    int rc;
    switch (m->kind) {
    case MM_CCCFG: case MM_CACFG: rc = cfg(&r, &m->u.cfg, 1); break;
    case MM_CCCFQ: rc = cfg(&r, &m->u.cfg, 0); break;
    case MM_CCCYC: case MM_CACYC: rc = cyc(&r, &m->u.cyc); break;
    case MM_CCTXD: case MM_CATXD: case MM_CARXD: rc = data(&r, &m->u.data, m->kind); break;
    case MM_CCMPC:
        rc = s->nfields < 2 ? fail(&r, "missing fields") : address(&r, 0, &m->u.ping.src) || address(&r, 1, &m->u.ping.dest);
        break;
    case MM_CADRQ: rc = drq(&r, &m->u.drq); break;
    case MM_CAACK: rc = ack(&r, &m->u.ack); break;
    case MM_CAERR: rc = err(&r, &m->u.err); break;
    case MM_CAREV: rc = rev(&r, &m->u.rev); break;
    case MM_CAXST: rc = xst(&r, &m->u.xst); break;
    case MM_CACST: rc = cst(&r, &m->u.cst); break;
    default:
        *why = "not in the subset";
        return 1;
    }
    if (rc) {
        *why = r.why ? r.why : "malformed";
        m->kind = MM_NONE;
        return -1;
    }
    *why = NULL;
    return 0;
}

/* ---- formatting: the same ranges, so what we write parses back. */

static int addr_ok(int a) { return a >= 0 && a <= MM_MAX_ADDRESS; }
static int flag_ok(int f) { return f == 0 || f == 1; }

/* snprintf's result: the length, or -1 when it did not fit. */
static int put(size_t n, int w) { return w < 0 || (size_t)w >= n ? -1 : w; }

static int put_hex(char *out, size_t n, int used, const uint8_t *d, int len)
{
    static const char digits[] = "0123456789ABCDEF";
    if (used < 0 || (size_t)used + 2 * (size_t)len >= n)
        return -1;
    for (int i = 0; i < len; i++) {
        out[used++] = digits[d[i] >> 4];
        out[used++] = digits[d[i] & 15];
    }
    out[used] = 0;
    return used;
}

/* HHMMSS of a time of day in [0, 86400), or "" for a negative one (no time). */
static void hhmmss(double t, char out[16])
{
    out[0] = 0;
    if (t >= 0 && t < 86400) {
        unsigned sec = (unsigned)t;
        snprintf(out, 16, "%02u%02u%02u", sec / 3600u, sec / 60u % 60u, sec % 60u);
    }
}

static int text_ok(const char *s) { return strpbrk(s, ",*$!\r\n") == NULL; }

int mm_format(const mm_msg *m, char *out, size_t n)
{
    const char *name = mm_kind_name(m->kind);
    switch (m->kind) {
    case MM_CCCFG: case MM_CACFG:
        if (!name_ok(m->u.cfg.name) || !value_ok(m->u.cfg.value))
            return -1;
        return put(n, snprintf(out, n, "%s,%s,%s", name, m->u.cfg.name, m->u.cfg.value));
    case MM_CCCFQ:
        if (!name_ok(m->u.cfg.name))
            return -1;
        return put(n, snprintf(out, n, "%s,%s", name, m->u.cfg.name));
    case MM_CCCYC: case MM_CACYC: {
        const mm_cyc *c = &m->u.cyc;
        if (c->cmd < 0 || c->cmd > 1000 || !addr_ok(c->src) || !addr_ok(c->dest) || mm_rate_frames(c->rate) < 0 ||
            !flag_ok(c->ack) || c->nframes < 1 || c->nframes > mm_rate_frames(c->rate))
            return -1;
        return put(n, snprintf(out, n, "%s,%d,%d,%d,%d,%d,%d", name, c->cmd, c->src, c->dest, c->rate, c->ack, c->nframes));
    }
    case MM_CCTXD: case MM_CATXD: case MM_CARXD: {
        const mm_data *d = &m->u.data;
        if (!addr_ok(d->src) || !addr_ok(d->dest) || !flag_ok(d->ack) || d->n < 0 || d->n > MM_MAX_FRAME_BYTES)
            return -1;
        if (m->kind == MM_CATXD)
            return put(n, snprintf(out, n, "%s,%d,%d,%d,%d", name, d->src, d->dest, d->ack, d->n));
        int used;
        if (m->kind == MM_CARXD) {
            if (d->frame < 1 || d->frame > MM_MAX_FRAMES)
                return -1;
            used = put(n, snprintf(out, n, "%s,%d,%d,%d,%d,", name, d->src, d->dest, d->ack, d->frame));
        } else {
            used = put(n, snprintf(out, n, "%s,%d,%d,%d,", name, d->src, d->dest, d->ack));
        }
        return put_hex(out, n, used, d->data, d->n);
    }
    case MM_CCMPC:
        if (!addr_ok(m->u.ping.src) || !addr_ok(m->u.ping.dest))
            return -1;
        return put(n, snprintf(out, n, "%s,%d,%d", name, m->u.ping.src, m->u.ping.dest));
    case MM_CADRQ: {
        const mm_drq *d = &m->u.drq;
        if (!addr_ok(d->src) || !addr_ok(d->dest) || !flag_ok(d->ack) || d->nbytes < 0 ||
            d->nbytes > MM_MAX_FRAME_BYTES || d->frame < 1 || d->frame > MM_MAX_FRAMES || d->time_s >= 86400)
            return -1;
        char t[16];
        hhmmss(d->time_s, t);
        return put(n, snprintf(out, n, "%s,%s,%d,%d,%d,%d,%d", name, t, d->src, d->dest, d->ack, d->nbytes, d->frame));
    }
    case MM_CAACK: {
        const mm_ack *a = &m->u.ack;
        if (!addr_ok(a->src) || !addr_ok(a->dest) || a->frame < 1 || a->frame > MM_MAX_FRAMES || a->ack > 1)
            return -1;
        if (a->ack < 0)
            return put(n, snprintf(out, n, "%s,%d,%d,%d", name, a->src, a->dest, a->frame));
        return put(n, snprintf(out, n, "%s,%d,%d,%d,%d", name, a->src, a->dest, a->frame, a->ack));
    }
    case MM_CAERR: case MM_CAREV: {
        double ts = m->kind == MM_CAERR ? m->u.err.time_s : m->u.rev.time_s;
        if (ts >= 86400)
            return -1;
        char t[16];
        hhmmss(ts, t);
        if (m->kind == MM_CAREV) {
            if (!m->u.rev.ident[0] || !text_ok(m->u.rev.ident) || !text_ok(m->u.rev.version))
                return -1;
            return put(n, snprintf(out, n, "%s,%s,%s,%s", name, t, m->u.rev.ident, m->u.rev.version));
        }
        const mm_err *e = &m->u.err;
        if (!text_ok(e->module) || strpbrk(e->text, "*$!\r\n") || e->number > 100000)
            return -1;
        if (e->number < 0)
            return put(n, snprintf(out, n, "%s,%s,%s,,%s", name, t, e->module, e->text));
        return put(n, snprintf(out, n, "%s,%s,%s,%d,%s", name, t, e->module, e->number, e->text));
    }
    default:
        return -1; /* statistics are read, never written by the host; the emulator writes its own */
    }
}
