#include "common/lcm_rx.h"

#include "common/lcm_chanfilter.h"
#include "common/lcm_validate.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct rx_sub {
    lcm_subscription_t *lcm_sub;
    const auv_type_entry_t *type;
    rx_handler_t handler;
    void *user;
    rx_stats_t stats;
    void *scratch;              /* one decoded struct, reused every message */
    int quiet_other_types;      /* wrong fingerprints are only counted */
    const void *raw;            /* the bytes being handled (rx_current_raw) */
    size_t raw_len;
};

int rx_decode(const auv_type_entry_t *type, const void *data, int len, void *out)
{
    const lcm_type_info_t *info = type->info();
    if (len < 8 || auv_fingerprint_of(data, (size_t)len) != info->get_hash())
        return -1;
    /* Validate before decoding: lcm-gen's decoders leak what they allocated
     * when they fail half-way. A payload that is longer than its message is
     * as wrong as one that is cut short: the sender used another layout. */
    if (lcm_validate_body(type, (const uint8_t *)data + 8, len - 8) != len - 8)
        return -2;
    memset(out, 0, type->struct_size);
    if (info->decode(data, 0, len, out) != len) {
        info->decode_cleanup(out);
        return -2;
    }
    return 0;
}

/* Report the first few failures per subscription, then only count them. */
static void report(rx_sub_t *s, const char *channel, const char *what, int len)
{
    uint64_t errors = s->stats.wrong_fingerprint + s->stats.malformed;
    if (errors <= 3)
        fprintf(stderr, "lcm_rx: %s: dropped %d-byte message (%s as %s)%s\n", channel, len, what,
                s->type->lcm_name, errors == 3 ? "; further drops are only counted" : "");
}

static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    rx_sub_t *s = user;
    s->stats.received++;
    int rc = rx_decode(s->type, rbuf->data, (int)rbuf->data_size, s->scratch);
    if (rc == -1) {
        s->stats.wrong_fingerprint++;
        if (!s->quiet_other_types) report(s, channel, "wrong fingerprint", (int)rbuf->data_size);
        return;
    }
    if (rc == -2) {
        s->stats.malformed++;
        report(s, channel, "truncated or malformed", (int)rbuf->data_size);
        return;
    }
    s->stats.delivered++;
    s->raw = rbuf->data;
    s->raw_len = rbuf->data_size;
    s->handler(channel, s->scratch, rbuf->recv_utime, s->user);
    s->raw = NULL;
    s->raw_len = 0;
    s->type->info()->decode_cleanup(s->scratch);
}

lcm_t *rx_lcm_create(const char *url)
{
    lcm_t *lcm = lcm_create(url);
    if (lcm)
        auv_chanfilter_register(lcm, auv_chanfilter_new(url));
    return lcm;
}

void rx_lcm_destroy(lcm_t *lcm)
{
    auv_chanfilter_unregister(lcm);
    if (lcm)
        lcm_destroy(lcm);
}

lcm_subscription_t *rx_subscribe_raw(lcm_t *lcm, const char *channel, lcm_msg_handler_t handler, void *user)
{
    return rx_subscribe_raw_where(lcm, channel, NULL, 0, 0, handler, user);
}

lcm_subscription_t *rx_subscribe_raw_where(lcm_t *lcm, const char *channel, const void *payload, int payload_at,
                                           int payload_len, lcm_msg_handler_t handler, void *user)
{
    auv_chanfilter_t *f = auv_chanfilter_of(lcm);
    const auv_chanfilter_rule_t rule = {channel, payload, payload_at, payload_len};
    if (auv_chanfilter_note_rule(f, &rule) < 0)
        return NULL;
    lcm_subscription_t *sub = lcm_subscribe(lcm, channel, handler, user);
    if (sub && auv_chanfilter_apply(f) < 0) {
        static int told;
        if (!told++)
            fprintf(stderr, "lcm_rx: the kernel refused the channel filter (%s): this process receives every channel\n",
                    strerror(errno));
    }
    return sub;
}

rx_sub_t *rx_subscribe(lcm_t *lcm, const char *channel, const auv_type_entry_t *type,
                       rx_handler_t handler, void *user)
{
    if (!lcm || !channel || !type || !handler)
        return NULL;
    rx_sub_t *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    s->scratch = calloc(1, type->struct_size);
    s->type = type;
    s->handler = handler;
    s->user = user;
    if (s->scratch)
        s->lcm_sub = rx_subscribe_raw(lcm, channel, on_message, s);
    if (!s->lcm_sub) {
        free(s->scratch);
        free(s);
        return NULL;
    }
    return s;
}

void rx_unsubscribe(lcm_t *lcm, rx_sub_t *sub)
{
    if (!sub)
        return;
    lcm_unsubscribe(lcm, sub->lcm_sub);
    free(sub->scratch);
    free(sub);
}

int rx_set_queue_capacity(rx_sub_t *sub, int capacity)
{
    return lcm_subscription_set_queue_capacity(sub->lcm_sub, capacity);
}

void rx_set_quiet_other_types(rx_sub_t *sub, int quiet)
{
    if (sub) sub->quiet_other_types = quiet;
}

const rx_stats_t *rx_stats(const rx_sub_t *sub) { return &sub->stats; }

const void *rx_current_raw(const rx_sub_t *sub, size_t *len)
{
    if (len)
        *len = sub ? sub->raw_len : 0;
    return sub ? sub->raw : NULL;
}

uint64_t rx_decode_errors(const rx_sub_t *sub)
{
    return sub->stats.wrong_fingerprint + sub->stats.malformed;
}
