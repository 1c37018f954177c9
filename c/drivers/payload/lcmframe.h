/* lcmframe: one LCM message carried whole over a byte link (a serial line, a
 * TCP port), for devices with no protocol of their own to copy: the
 * sidescan's contacts and the identify sensor's looks, whose sonar and ATR
 * computer stand behind them (docs/drivers.md, "auv-payload").
 *
 *   offset  size  field
 *   0       2     sync A5 4C
 *   2       1     T: the topic's length, 1..LCMFRAME_MAX_TOPIC
 *   3       T     the topic: the channel's suffix ("CONTACTS": <V>.CONTACTS),
 *                 'A'-'Z', '0'-'9', '_'
 *   3+T     2     N: the payload's length, big-endian, 1..LCMFRAME_MAX_PAYLOAD
 *   5+T     N     the payload: the message's LCM encoding, fingerprint first
 *                 (exactly the bytes lcm_publish sends)
 *   5+T+N   2     CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, not
 *                 reflected, no final XOR; "123456789" gives 0x29B1),
 *                 big-endian, over every byte before it from the sync on
 *
 * The framer takes any bytes in any reads. A refused header or a bad CRC
 * starts the search again one byte after the refused sync, so a frame that
 * began inside a broken one is still found; a length over the bound is
 * refused at the header, never buffered. No allocation: the largest frame
 * fits in the framer. Pure code: no LCM, no I/O, no clock. */
#ifndef DRIVERS_LCMFRAME_H
#define DRIVERS_LCMFRAME_H

#include <stddef.h>
#include <stdint.h>

#define LCMFRAME_SYNC0 0xA5
#define LCMFRAME_SYNC1 0x4C
#define LCMFRAME_MAX_TOPIC 32
#define LCMFRAME_MAX_PAYLOAD 4096 /* a contact is some 150 bytes: room for larger payloads, no more */
#define LCMFRAME_OVERHEAD 7       /* sync, T, N, CRC */
#define LCMFRAME_MAX (LCMFRAME_OVERHEAD + LCMFRAME_MAX_TOPIC + LCMFRAME_MAX_PAYLOAD)

typedef enum {
    LCMFRAME_NONE = -1,  /* nothing complete with this byte */
    LCMFRAME_OK = 0,     /* a frame: topic and payload in the framer */
    LCMFRAME_BAD_HEADER, /* a topic length 0 or over the bound, a byte outside the topic's alphabet, N = 0 */
    LCMFRAME_TOO_LONG,   /* N over LCMFRAME_MAX_PAYLOAD */
    LCMFRAME_BAD_CRC,
    LCMFRAME_RESULT_COUNT
} lcmframe_result;

/* "bad header", "too long", "bad crc": the drivers' refusal reasons. */
const char *lcmframe_result_name(lcmframe_result r);

uint16_t lcmframe_crc16(const uint8_t *data, size_t n);

/* The frame of (topic, payload) into out (size cap): its length, or -1 if
 * the topic or the payload is out of bounds or it does not fit. */
int lcmframe_encode(uint8_t *out, size_t cap, const char *topic, const uint8_t *payload, size_t n);

typedef struct {
    uint8_t buf[LCMFRAME_MAX];
    size_t len;          /* bytes of the frame under way (0: hunting) */
    size_t need;         /* its whole length once the header is read (0: not yet) */
    uint64_t garbage;    /* bytes outside any frame, ever */
    /* the frame just completed (valid after LCMFRAME_OK until the next push) */
    char topic[LCMFRAME_MAX_TOPIC + 1];
    const uint8_t *payload;
    size_t payload_len;
    /* bytes of a refused frame to search again (after its sync), and where */
    uint8_t again[LCMFRAME_MAX];
    size_t again_len, again_at;
} lcmframe_framer;

void lcmframe_init(lcmframe_framer *f);

/* One byte of the stream: LCMFRAME_OK when a frame completed and its CRC
 * checked, a refusal when a frame was refused, LCMFRAME_NONE otherwise. After
 * a refusal call lcmframe_pending() until it returns LCMFRAME_NONE: the
 * refused frame's bytes after its sync are searched again (each may complete
 * or refuse a frame in turn). */
lcmframe_result lcmframe_push(lcmframe_framer *f, uint8_t byte);
lcmframe_result lcmframe_pending(lcmframe_framer *f);

/* A frame under way (its sync seen, not complete): for a silence that cuts
 * it, and to tell a new frame from a lone first sync byte in garbage. */
static inline int lcmframe_in_frame(const lcmframe_framer *f) { return f->len >= 2; }

#endif
