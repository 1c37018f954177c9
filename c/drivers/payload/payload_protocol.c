/* auv-payload's protocol: lcmframe frames (lcmframe.c) into the messages
 * they carry, each decoded strictly as its topic's type before its bytes
 * are published unchanged (payload.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/lcm_rx.h"
#include "drivers/payload/payload.h"

#define DEFAULT_FRAME_TIMEOUT_S 0.5

const payload_topic payload_topics[] = {
    {"CONTACTS", "sidescan_contact_t"}, /* the sidescan's detections (python/sim/sonar/publisher.py) */
    {"LOOKS", "reacquire_look_t"},      /* the identify sensor's looks (python/sim/sonar/identify.py) */
    {0},
};

static int set_frame_timeout(void *state, const char *v, char *err, size_t n)
{
    payload_state *s = state;
    char *end;
    double d = strtod(v, &end);
    if (end == v || *end || !(d >= 0.01 && d <= 10.0)) {
        snprintf(err, n, "--frame-timeout wants seconds in [0.01, 10], not '%s'", v);
        return -1;
    }
    s->frame_timeout_s = d;
    s->timeout_set = 1;
    return 0;
}

static int payload_init(void *state, drv_ctx *ctx)
{
    payload_state *s = state;
    if (!s->timeout_set)
        s->frame_timeout_s = DEFAULT_FRAME_TIMEOUT_S;
    lcmframe_init(&s->framer);
    s->last_byte = -1;
    size_t biggest = 0;
    for (int i = 0; payload_topics[i].topic; i++) {
        s->types[i] = auv_type_find(payload_topics[i].type_name);
        if (!s->types[i]) {
            drv_log(ctx, "%s is not in the type table", payload_topics[i].type_name);
            return -1;
        }
        if (s->types[i]->struct_size > biggest)
            biggest = s->types[i]->struct_size;
    }
    if (biggest > sizeof s->scratch) {
        drv_log(ctx, "a decoded message takes %zu bytes, over the %zu of PAYLOAD_SCRATCH", biggest,
                sizeof s->scratch);
        return -1;
    }
    return 0;
}

static void on_frame(payload_state *s, drv_ctx *ctx, int64_t stamp)
{
    const lcmframe_framer *f = &s->framer;
    int k = 0;
    while (payload_topics[k].topic && strcmp(payload_topics[k].topic, f->topic) != 0)
        k++;
    if (!payload_topics[k].topic) {
        drv_drop(ctx, "unknown topic", "%s (%zu bytes)", f->topic, f->payload_len);
        return;
    }
    /* strictly its topic's type: the fingerprint, and every byte (none more
     * or less), as the framework's subscriptions decode */
    const auv_type_entry_t *type = s->types[k];
    int r = rx_decode(type, f->payload, (int)f->payload_len, s->scratch);
    if (r != 0) {
        drv_drop(ctx, "undecodable", "%s: %zu bytes are not a %s (%s)", f->topic, f->payload_len, type->lcm_name,
                 r == -1 ? "another fingerprint" : "malformed");
        return;
    }
    type->info()->decode_cleanup(s->scratch);
    drv_frame_ok(ctx, stamp);
    drv_publish_encoded(ctx, f->topic, type, f->payload, (int)f->payload_len);
}

static void on_result(payload_state *s, drv_ctx *ctx, lcmframe_result r, int64_t stamp)
{
    if (r == LCMFRAME_OK) {
        on_frame(s, ctx, stamp);
    } else if (r > LCMFRAME_OK) {
        drv_drop(ctx, lcmframe_result_name(r), "a frame refused at byte %llu of the garbage count",
                 (unsigned long long)s->framer.garbage);
        /* its bytes searched again and skipped are the rest of it: not a new run of garbage */
        s->in_garbage = 1;
        s->garbage_seen = s->framer.garbage;
    }
}

static void count_garbage(payload_state *s, drv_ctx *ctx, uint8_t byte)
{
    if (s->framer.garbage != s->garbage_seen) {
        s->garbage_seen = s->framer.garbage;
        if (!s->in_garbage)
            drv_drop(ctx, "garbage", "bytes outside any frame, from 0x%02x", byte);
        s->in_garbage = 1;
    } else if (lcmframe_in_frame(&s->framer)) {
        s->in_garbage = 0;
    }
}

static void payload_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    payload_state *s = state;
    s->last_byte = stamp;
    for (size_t i = 0; i < n; i++) {
        /* the byte, then what a refusal left to search again, to the end */
        lcmframe_result r = lcmframe_push(&s->framer, bytes[i]);
        do {
            on_result(s, ctx, r, stamp);
            count_garbage(s, ctx, bytes[i]);
        } while ((r = lcmframe_pending(&s->framer)) != LCMFRAME_NONE);
    }
}

static void payload_tick(void *state, drv_ctx *ctx, int64_t now)
{
    payload_state *s = state;
    /* a frame the link stopped sending in the middle: it will never end, and
     * the next frame must not be read as its rest */
    if (lcmframe_in_frame(&s->framer) && s->last_byte >= 0 &&
        now - s->last_byte > (int64_t)(s->frame_timeout_s * 1e6)) {
        drv_drop(ctx, "truncated frame", "%zu bytes, then %.2f s of silence", s->framer.len,
                 (double)(now - s->last_byte) / 1e6);
        uint64_t garbage = s->framer.garbage;
        lcmframe_init(&s->framer);
        s->framer.garbage = garbage;
    }
}

static void payload_reset(void *state, drv_ctx *ctx)
{
    payload_state *s = state;
    (void)ctx;
    uint64_t garbage = s->framer.garbage; /* a half frame of a lost stream never ends */
    lcmframe_init(&s->framer);
    s->framer.garbage = garbage;
    s->in_garbage = 0;
}

static const drv_flag payload_flags[] = {
    {"--frame-timeout", "S", "a frame with no byte for S seconds is dropped as truncated (default 0.5)",
     set_frame_timeout},
    {0},
};

const drv_protocol payload_protocol = {
    .device = "PAYLOAD",
    .program = "auv-payload",
    .summary = "The payload link of hardware in the loop at the wire: lcmframe frames (sync A5 4C, topic,\n"
               "length, an LCM-encoded message, CRC-16/CCITT) from the simulator's sonar and identify\n"
               "sensor; each message that decodes strictly as its topic's type (CONTACTS: sidescan_contact_t,\n"
               "LOOKS: reacquire_look_t) is published unchanged on <ID>.<TOPIC>.",
    .default_baud = 115200,
    .state_size = sizeof(payload_state),
    .flags = payload_flags,
    .link_time = 1,
    .init = payload_init,
    .feed = payload_feed,
    .tick = payload_tick,
    .reset = payload_reset,
};

DRV_REGISTER(payload_protocol)
