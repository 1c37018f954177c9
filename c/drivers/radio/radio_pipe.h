/* The radio as a byte pipe (docs/radio.md, "The byte pipe"): each encoded
 * radio_frame_t goes on the serial line or TCP port of a transparent radio
 * modem as
 *
 *     0xA5 0x5A | length (4 bytes, big endian) | the frame | CRC-32 (4 bytes, big endian)
 *
 * (the CRC as zlib computes it, over the frame's bytes only). The reader finds
 * frames in the byte stream and, after anything that does not check (noise, a
 * wrong CRC, a length over RP_MAX_FRAME, a frame cut by a dive), skips to the
 * next marker, so a damaged frame costs that frame and nothing after it. The
 * same framing is python/tools/radio/pipe.py's; tests hold the two together. */
#ifndef RADIO_PIPE_H
#define RADIO_PIPE_H

#include <stddef.h>
#include <stdint.h>

#include "drivers/common/drv_ctx.h"

#define RP_MARK0 0xA5
#define RP_MARK1 0x5A
#define RP_HEAD 6                /* marker and length */
#define RP_OVERHEAD 10           /* and the CRC */
#define RP_MAX_FRAME 16384       /* an encoded radio_frame_t: a 4 KiB chunk and its header fit */

typedef void (*rp_frame_fn)(void *user, const uint8_t *frame, size_t n);

typedef struct {
    uint8_t buf[RP_OVERHEAD + RP_MAX_FRAME];
    size_t len;
    int64_t noise_bytes; /* bytes outside any frame, skipped */
} rp_deframer;

/* Any bytes in; each frame whose length and CRC check goes to on_frame (the
 * encoded radio_frame_t, not yet decoded). Drops are counted on ctx:
 * "noise bytes", "too long", "bad CRC". */
void rp_feed(rp_deframer *d, drv_ctx *ctx, const uint8_t *data, size_t n, rp_frame_fn on_frame, void *user);

/* Forget a half frame (the pipe was lost). */
void rp_reset(rp_deframer *d);

/* Frame n bytes into out (n + RP_OVERHEAD bytes); the size written, or 0 if
 * n is over RP_MAX_FRAME or out too small. */
size_t rp_encode(const uint8_t *frame, size_t n, uint8_t *out, size_t cap);

#endif
