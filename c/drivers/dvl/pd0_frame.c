/* PD0 framing: find 7F 7F, read the length, wait for the whole ensemble,
 * check its sum and its offset table. See pd0.h. */
#include <string.h>

#include "drivers/dvl/pd0.h"

static const char *const names[PD0_RESULT_COUNT] = {
    [PD0_OK] = "ok",
    [PD0_BAD_CHECKSUM] = "bad checksum",
    [PD0_BAD_LENGTH] = "bad length",
    [PD0_BAD_HEADER] = "bad header",
    [PD0_TRUNCATED] = "truncated ensemble",
    [PD0_BAD_OFFSET] = "offset outside ensemble",
    [PD0_SHORT_TYPE] = "data type cut short",
    [PD0_DUPLICATE_TYPE] = "duplicate data type",
    [PD0_NO_FIXED_LEADER] = "no fixed leader",
    [PD0_NO_VARIABLE_LEADER] = "no variable leader",
    [PD0_BAD_BEAMS] = "bad beam count",
    [PD0_BAD_BEAM_ANGLE] = "bad beam angle",
    [PD0_BAD_ATTITUDE] = "attitude out of range",
};

const char *pd0_result_name(pd0_result r)
{
    return (unsigned)r < PD0_RESULT_COUNT ? names[r] : "unknown";
}

uint16_t pd0_checksum(const uint8_t *p, size_t n)
{
    uint32_t s = 0;
    for (size_t i = 0; i < n; i++)
        s += p[i];
    return (uint16_t)s;
}

static unsigned u16(const uint8_t *p) { return (unsigned)p[0] | (unsigned)p[1] << 8; }

/* The bytes up to the checksum: 16 bits at 3-4 and, the Pathfinder's manual
 * says, the "spare" byte 5 as their MSB (a checksum offset of 24 bits; the
 * Workhorse's manual calls it spare and sends 0). */
size_t pd0__length(const uint8_t *p);
size_t pd0__length(const uint8_t *p) { return (size_t)u16(p + 2) | (size_t)p[4] << 16; }

/* The checks of a header whose first `have` bytes are known; the framer
 * calls it as bytes arrive, the decoder with the whole buffer. Returns
 * PD0_OK when what is known is fine, *need set to the bytes still needed
 * before more can be said (0 once the whole ensemble and its sum are
 * known and good). The offset table is checked as soon as it is in, before
 * the bytes its length asks for: a 7F 7F in garbage (its length anything up
 * to 64 kB, a minute of a 9600-baud stream) is refused at once, not held. */
static pd0_result check_header(const uint8_t *p, size_t have, size_t *need)
{
    if (have < 5) {
        *need = 5;
        return PD0_OK;
    }
    size_t nbytes = pd0__length(p);
    /* 6 header bytes and one offset at least; longer than the framer holds
     * (no unit sends that much: a false 7F 7F, or a broken length) */
    if (nbytes < 8 || nbytes > PD0_MAX_ENSEMBLE)
        return PD0_BAD_LENGTH;
    if (have < 6) {
        *need = 6;
        return PD0_OK;
    }
    size_t ntypes = p[5];
    if (ntypes == 0)
        return PD0_BAD_HEADER;
    size_t header = 6 + 2 * ntypes;
    if (header > nbytes)
        return PD0_BAD_LENGTH;
    if (have < header) {
        *need = header;
        return PD0_OK;
    }
    /* the first data type right after the offsets, each one's ID inside the
     * ensemble, in order: a data type's bytes run to the next one's offset */
    size_t prev = 0;
    for (size_t i = 0; i < ntypes; i++) {
        size_t off = u16(p + 6 + 2 * i);
        if ((i == 0 && off != header) || off + 2 > nbytes || off <= prev)
            return PD0_BAD_OFFSET;
        prev = off;
    }
    if (have < nbytes + 2) {
        *need = nbytes + 2;
        return PD0_OK;
    }
    if (pd0_checksum(p, nbytes) != u16(p + nbytes))
        return PD0_BAD_CHECKSUM;
    *need = 0;
    return PD0_OK;
}

/* Exposed to pd0_decode.c, which re-checks a buffer given to it. */
pd0_result pd0__check_whole(const uint8_t *p, size_t n);
pd0_result pd0__check_whole(const uint8_t *p, size_t n)
{
    if (n < 2 || p[0] != 0x7F || p[1] != 0x7F)
        return PD0_BAD_HEADER;
    size_t need = 0;
    pd0_result r = check_header(p, n, &need);
    if (r != PD0_OK)
        return r;
    return need ? PD0_TRUNCATED : PD0_OK;
}

void pd0_framer_init(pd0_framer *f) { memset(f, 0, sizeof *f); }

/* A waves packet's second byte: 7F 79 (a Workhorse with the waves option
 * sends them between its ensembles, framed as PD0). */
#define WAVES_ID 0x79

/* Drops bytes before the next possible header (7F 7F or 7F 79, or a 7F last). */
static void align(pd0_framer *f)
{
    while (f->start < f->len) {
        const uint8_t *p = f->buf + f->start;
        size_t left = f->len - f->start;
        if (p[0] == 0x7F && (left == 1 || p[1] == 0x7F || p[1] == WAVES_ID))
            return;
        f->start++;
        f->garbage_bytes++;
    }
}

/* What the held bytes make: an ensemble, a refusal, or -1 (need more). */
static int scan(pd0_framer *f, const uint8_t **ens, size_t *ens_len)
{
    for (;;) {
        align(f);
        size_t have = f->len - f->start, need = 0;
        if (have < 2 || have < f->need)
            return -1;
        f->need = 0;
        const uint8_t *p = f->buf + f->start;
        pd0_result r = check_header(p, have, &need);
        if (p[1] == WAVES_ID) {
            /* not an ensemble: skipped whole when its sum is good, else its
             * first byte is garbage (nothing the driver decodes was lost) */
            if (r == PD0_OK && need) {
                f->need = need;
                return -1;
            }
            if (r == PD0_OK) {
                f->start += pd0__length(p) + 2;
                f->waves_packets++;
            } else {
                f->start++;
                f->garbage_bytes++;
            }
            continue;
        }
        if (r != PD0_OK) {
            f->start++; /* resync one byte after the refused header */
            return r;
        }
        if (need) {
            f->need = need;
            return -1;
        }
        *ens = p;
        *ens_len = pd0__length(p) + 2;
        f->deliver = *ens_len;
        return PD0_OK;
    }
}

int pd0_framer_push(pd0_framer *f, const uint8_t *data, size_t n, size_t *used, const uint8_t **ens,
                    size_t *ens_len)
{
    *used = 0;
    if (f->deliver) {
        f->start += f->deliver;
        f->deliver = 0;
    }
    for (;;) {
        int r = scan(f, ens, ens_len);
        if (r != -1)
            return r;
        if (*used == n)
            return -1;
        /* room for more: move the held bytes to the front when the end is full */
        if (f->len == sizeof f->buf) {
            memmove(f->buf, f->buf + f->start, f->len - f->start);
            f->len -= f->start;
            f->start = 0;
        }
        if (f->start == f->len)
            f->start = f->len = 0;
        size_t take = sizeof f->buf - f->len;
        if (take > n - *used)
            take = n - *used;
        memcpy(f->buf + f->len, data + *used, take);
        f->len += take;
        *used += take;
    }
}

int pd0_framer_flush(pd0_framer *f)
{
    if (f->deliver) {
        f->start += f->deliver;
        f->deliver = 0;
    }
    size_t have = f->len - f->start;
    int r = -1;
    if (have >= 4 && f->buf[f->start + 1] == 0x7F)
        r = PD0_TRUNCATED; /* a header with its length was held: an ensemble was cut */
    else
        f->garbage_bytes += have; /* too little to be a header, or a waves packet cut */
    f->start = f->len = 0;
    f->need = 0;
    return r;
}
