/* The classic BPF program of a channel filter (lcm_chanfilter.h).
 *
 * A UDP socket's filter sees the datagram from its UDP header: the LCM header
 * starts at byte 8 (magic, sequence number), the channel name at byte 16,
 * NUL-terminated. Per pattern the program compares the name a word at a time
 * (masking out `.` wildcards), the last bytes one at a time, and first checks
 * the datagram is long enough: a load past its end would end the whole
 * program with "drop", before a later pattern could accept it. A rule's
 * payload condition is more bytes to compare after the name's terminator. */
#include "common/lcm_chanfilter.h"

#include <linux/filter.h>
#include <stdint.h>
#include <string.h>

#define LCM_SHORT_MAGIC 0x4c433032u /* "LC02": one datagram, one message */
#define UDP_HEADER 8
#define NAME_AT (UDP_HEADER + 8)
#define MAX_NAME 128  /* liblcm refuses channels over 63; a longer pattern is not a name */
#define MAX_BYTES 224 /* the name and a payload condition: every jump stays within 255 */
#define ACCEPT 0xffffffffu

typedef struct {
    uint8_t byte[MAX_BYTES];
    uint8_t care[MAX_BYTES]; /* 0: a `.` (any byte) */
    int n;                   /* bytes to compare, the terminator included unless a prefix */
    int prefix;
} name_pattern_t;

static int is_meta(char c) { return c && strchr(".[]()*+?{}|^$\\", c) != NULL; }

/* What lcm_subscribe("^" pattern "$") matches, as bytes to compare, when the
 * pattern is a name: literal characters, `\` before a metacharacter, `.`, and
 * an optional trailing `.*`. -1 for anything else. */
static int parse(const char *p, name_pattern_t *out)
{
    size_t len = strlen(p);
    if (len && p[0] == '^')
        p++, len--;
    if (len && p[len - 1] == '$' && (len < 2 || p[len - 2] != '\\'))
        len--;
    int prefix = len >= 2 && p[len - 2] == '.' && p[len - 1] == '*' && (len < 3 || p[len - 3] != '\\');
    if (prefix)
        len -= 2;
    int k = 0;
    for (size_t i = 0; i < len; i++) {
        if (k >= MAX_NAME)
            return -1;
        char c = p[i];
        if (c == '\\') {
            if (i + 1 >= len || !is_meta(p[i + 1]))
                return -1; /* \d, \w, a trailing backslash: not a name */
            out->byte[k] = (uint8_t)p[++i];
            out->care[k++] = 1;
        } else if (c == '.') {
            out->byte[k] = 0;
            out->care[k++] = 0;
        } else if (is_meta(c)) {
            return -1;
        } else {
            out->byte[k] = (uint8_t)c;
            out->care[k++] = 1;
        }
    }
    if (!prefix) {
        out->byte[k] = 0; /* the name ends here */
        out->care[k++] = 1;
    } else if (k == 0) {
        return -1; /* `.*`: every channel */
    }
    out->n = k;
    out->prefix = prefix;
    return 0;
}

/* A payload condition follows the name at a known place only when the name's
 * length is known: after a prefix it is ignored (the rule is wider, never
 * narrower, than asked). */
static int add_payload(name_pattern_t *m, const auv_chanfilter_rule_t *r)
{
    if (!r->payload || m->prefix || r->payload_len <= 0)
        return 0;
    if (r->payload_at < 0 || m->n + r->payload_at + r->payload_len > MAX_BYTES)
        return -1;
    for (int i = 0; i < r->payload_at; i++)
        m->care[m->n++] = 0;
    for (int i = 0; i < r->payload_len; i++) {
        m->byte[m->n] = ((const uint8_t *)r->payload)[i];
        m->care[m->n++] = 1;
    }
    return 0;
}

typedef struct {
    struct sock_filter *ins;
    int n, cap;
} prog_t;

static int emit(prog_t *p, uint16_t code, uint8_t jt, uint8_t jf, uint32_t k)
{
    if (p->n >= p->cap)
        return -1;
    p->ins[p->n++] = (struct sock_filter){code, jt, jf, k};
    return 0;
}

/* One pattern's block: every mismatch jumps past its final "accept". */
static int emit_pattern(prog_t *p, const name_pattern_t *m)
{
    int start = p->n, rc = 0;
    rc |= emit(p, BPF_LD | BPF_W | BPF_LEN, 0, 0, 0);
    rc |= emit(p, BPF_JMP | BPF_JGE | BPF_K, 0, 0, (uint32_t)(NAME_AT + m->n));
    int i = 0;
    for (; i + 4 <= m->n; i += 4) {
        uint32_t val = 0, mask = 0;
        for (int b = 0; b < 4; b++) {
            val = val << 8 | m->byte[i + b];
            mask = mask << 8 | (m->care[i + b] ? 0xffu : 0);
        }
        if (!mask)
            continue;
        rc |= emit(p, BPF_LD | BPF_W | BPF_ABS, 0, 0, (uint32_t)(NAME_AT + i));
        if (mask != 0xffffffffu)
            rc |= emit(p, BPF_ALU | BPF_AND | BPF_K, 0, 0, mask);
        rc |= emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, 0, val & mask);
    }
    for (; i < m->n; i++) {
        if (!m->care[i])
            continue;
        rc |= emit(p, BPF_LD | BPF_B | BPF_ABS, 0, 0, (uint32_t)(NAME_AT + i));
        rc |= emit(p, BPF_JMP | BPF_JEQ | BPF_K, 0, 0, m->byte[i]);
    }
    rc |= emit(p, BPF_RET | BPF_K, 0, 0, ACCEPT);
    if (rc)
        return -1;
    int end = p->n; /* the next block */
    for (int j = start; j < end; j++) {
        struct sock_filter *in = &p->ins[j];
        if (BPF_CLASS(in->code) == BPF_JMP) {
            if (end - j - 1 > 255)
                return -1;
            in->jf = (uint8_t)(end - j - 1);
        }
    }
    return 0;
}

int auv_chanfilter_compile(const auv_chanfilter_rule_t *rules, int n, void *out, int cap)
{
    prog_t p = {out, 0, cap};
    int rc = 0;
    /* not an unfragmented LCM datagram: not ours to judge */
    rc |= emit(&p, BPF_LD | BPF_W | BPF_LEN, 0, 0, 0);
    rc |= emit(&p, BPF_JMP | BPF_JGE | BPF_K, 1, 0, NAME_AT + 1);
    rc |= emit(&p, BPF_RET | BPF_K, 0, 0, ACCEPT);
    rc |= emit(&p, BPF_LD | BPF_W | BPF_ABS, 0, 0, UDP_HEADER);
    rc |= emit(&p, BPF_JMP | BPF_JEQ | BPF_K, 1, 0, LCM_SHORT_MAGIC);
    rc |= emit(&p, BPF_RET | BPF_K, 0, 0, ACCEPT);
    if (rc)
        return -1;
    for (int i = 0; i < n; i++) {
        name_pattern_t m;
        if (parse(rules[i].channel, &m) < 0 || add_payload(&m, &rules[i]) < 0)
            return 0;
        if (emit_pattern(&p, &m) < 0)
            return -1;
    }
    if (emit(&p, BPF_RET | BPF_K, 0, 0, 0) < 0)
        return -1;
    return p.n;
}
