#include "drivers/radio/radio_pipe.h"

#include <string.h>

#include "common/crc32.h"

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | (uint32_t)p[3];
}

static void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static void consume(rp_deframer *d, size_t k)
{
    memmove(d->buf, d->buf + k, d->len - k);
    d->len -= k;
}

static void noise(rp_deframer *d, drv_ctx *ctx, size_t k)
{
    d->noise_bytes += (int64_t)k;
    drv_drop(ctx, "noise bytes", "%zu bytes outside any frame", k);
    consume(d, k);
}

/* The frames in the buffer, as far as it holds whole ones. */
static void scan(rp_deframer *d, drv_ctx *ctx, rp_frame_fn on_frame, void *user)
{
    for (;;) {
        size_t start = 0;
        while (start + 1 < d->len && !(d->buf[start] == RP_MARK0 && d->buf[start + 1] == RP_MARK1))
            start++;
        if (start + 1 >= d->len) { /* no marker: keep the last byte, a marker may begin there */
            if (d->len > 1)
                noise(d, ctx, d->len - 1);
            return;
        }
        if (start)
            noise(d, ctx, start);
        if (d->len < RP_HEAD)
            return;
        uint32_t n = be32(d->buf + 2);
        if (n > RP_MAX_FRAME) {
            drv_drop(ctx, "too long", "a frame of %u bytes (at most %d)", (unsigned)n, RP_MAX_FRAME);
            consume(d, 2); /* past this marker: the next one may start a good frame */
            continue;
        }
        if (d->len < RP_OVERHEAD + n)
            return;
        if (crc32_update(0, d->buf + RP_HEAD, n) != be32(d->buf + RP_HEAD + n)) {
            drv_drop(ctx, "bad CRC", "a frame of %u bytes", (unsigned)n);
            consume(d, 2);
            continue;
        }
        on_frame(user, d->buf + RP_HEAD, n);
        consume(d, RP_OVERHEAD + n);
    }
}

void rp_feed(rp_deframer *d, drv_ctx *ctx, const uint8_t *data, size_t n, rp_frame_fn on_frame, void *user)
{
    while (n) {
        size_t k = sizeof d->buf - d->len;
        if (k > n)
            k = n;
        memcpy(d->buf + d->len, data, k);
        d->len += k;
        data += k;
        n -= k;
        scan(d, ctx, on_frame, user); /* a full buffer always holds a whole frame or a skip */
    }
}

void rp_reset(rp_deframer *d) { d->len = 0; }

size_t rp_encode(const uint8_t *frame, size_t n, uint8_t *out, size_t cap)
{
    if (n > RP_MAX_FRAME || cap < n + RP_OVERHEAD)
        return 0;
    out[0] = RP_MARK0;
    out[1] = RP_MARK1;
    put_be32(out + 2, (uint32_t)n);
    memcpy(out + RP_HEAD, frame, n);
    put_be32(out + RP_HEAD + n, crc32_update(0, frame, n));
    return n + RP_OVERHEAD;
}
