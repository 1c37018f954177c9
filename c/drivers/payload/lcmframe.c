/* lcmframe framing (lcmframe.h): a byte-at-a-time state machine over one
 * buffer; a refused frame's bytes after its sync are searched again. */
#include "drivers/payload/lcmframe.h"

#include <string.h>

const char *lcmframe_result_name(lcmframe_result r)
{
    static const char *n[LCMFRAME_RESULT_COUNT] = {"ok", "bad header", "too long", "bad crc"};
    return (unsigned)r < LCMFRAME_RESULT_COUNT ? n[r] : "?";
}

uint16_t lcmframe_crc16(const uint8_t *data, size_t n)
{
    uint16_t crc = 0xFFFF;
    for (size_t i = 0; i < n; i++) {
        crc ^= (uint16_t)(data[i] << 8);
        for (int b = 0; b < 8; b++)
            crc = (uint16_t)(crc & 0x8000 ? (crc << 1) ^ 0x1021 : crc << 1);
    }
    return crc;
}

static int topic_char(uint8_t c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }

int lcmframe_encode(uint8_t *out, size_t cap, const char *topic, const uint8_t *payload, size_t n)
{
    size_t t = strlen(topic);
    if (t == 0 || t > LCMFRAME_MAX_TOPIC || n == 0 || n > LCMFRAME_MAX_PAYLOAD || cap < LCMFRAME_OVERHEAD + t + n)
        return -1;
    for (size_t i = 0; i < t; i++)
        if (!topic_char((uint8_t)topic[i]))
            return -1;
    size_t k = 0;
    out[k++] = LCMFRAME_SYNC0;
    out[k++] = LCMFRAME_SYNC1;
    out[k++] = (uint8_t)t;
    memcpy(out + k, topic, t);
    k += t;
    out[k++] = (uint8_t)(n >> 8);
    out[k++] = (uint8_t)n;
    memcpy(out + k, payload, n);
    k += n;
    uint16_t crc = lcmframe_crc16(out, k);
    out[k++] = (uint8_t)(crc >> 8);
    out[k++] = (uint8_t)crc;
    return (int)k;
}

void lcmframe_init(lcmframe_framer *f) { memset(f, 0, sizeof *f); }

/* Refuse the frame under way: its bytes after the sync go before whatever
 * was still to be searched again (they came from there, or from the stream
 * just now, so they fit). */
static lcmframe_result refuse(lcmframe_framer *f, lcmframe_result r)
{
    size_t rest = f->again_len - f->again_at, keep = f->len - 1;
    memmove(f->again + keep, f->again + f->again_at, rest);
    memcpy(f->again, f->buf + 1, keep);
    f->again_len = keep + rest;
    f->again_at = 0;
    f->len = f->need = 0;
    return r;
}

static lcmframe_result step(lcmframe_framer *f, uint8_t byte)
{
    if (f->len == 0) {
        if (byte == LCMFRAME_SYNC0)
            f->buf[f->len++] = byte;
        else
            f->garbage++;
        return LCMFRAME_NONE;
    }
    if (f->len == 1 && byte != LCMFRAME_SYNC1) {
        f->garbage++; /* the lone first sync byte; this byte may start a frame */
        f->len = 0;
        return step(f, byte);
    }
    f->buf[f->len++] = byte;
    if (f->len < 3)
        return LCMFRAME_NONE;
    size_t t = f->buf[2];
    if (t == 0 || t > LCMFRAME_MAX_TOPIC || (f->len > 3 && f->len <= 3 + t && !topic_char(byte)))
        return refuse(f, LCMFRAME_BAD_HEADER);
    if (f->len == 5 + t) {
        size_t n = (size_t)f->buf[3 + t] << 8 | f->buf[4 + t];
        if (n == 0)
            return refuse(f, LCMFRAME_BAD_HEADER);
        if (n > LCMFRAME_MAX_PAYLOAD)
            return refuse(f, LCMFRAME_TOO_LONG);
        f->need = LCMFRAME_OVERHEAD + t + n;
    }
    if (!f->need || f->len < f->need)
        return LCMFRAME_NONE;
    uint16_t crc = (uint16_t)(f->buf[f->len - 2] << 8 | f->buf[f->len - 1]);
    if (crc != lcmframe_crc16(f->buf, f->len - 2))
        return refuse(f, LCMFRAME_BAD_CRC);
    memcpy(f->topic, f->buf + 3, t);
    f->topic[t] = '\0';
    f->payload = f->buf + 5 + t;
    f->payload_len = f->len - LCMFRAME_OVERHEAD - t;
    f->len = f->need = 0;
    return LCMFRAME_OK;
}

lcmframe_result lcmframe_push(lcmframe_framer *f, uint8_t byte) { return step(f, byte); }

lcmframe_result lcmframe_pending(lcmframe_framer *f)
{
    while (f->again_at < f->again_len) {
        lcmframe_result r = step(f, f->again[f->again_at++]);
        if (r != LCMFRAME_NONE)
            return r;
    }
    f->again_len = f->again_at = 0;
    return LCMFRAME_NONE;
}
