#include "common/lcm_rx.h"

#include "common/lcm_chanfilter.h"
#include "common/lcm_rx_route.h"
#include "common/lcm_validate.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct rx_sub {
    rx_raw_t *route;
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
    /* its own socket where it can (lcm_rx_own.c); else liblcm receives,
     * behind a channel filter on liblcm's socket */
    if (lcm && !rx_own_create(lcm, url))
        auv_chanfilter_register(lcm, auv_chanfilter_new(url));
    return lcm;
}

void rx_lcm_destroy(lcm_t *lcm)
{
    rx_own_destroy(lcm);
    auv_chanfilter_unregister(lcm);
    if (lcm)
        lcm_destroy(lcm);
}

int rx_handle_timeout(lcm_t *lcm, int timeout_ms)
{
    rx_own_t *own = rx_own_of(lcm);
    return own ? rx_own_handle_timeout(own, timeout_ms) : lcm_handle_timeout(lcm, timeout_ms);
}

rx_raw_t *rx_subscribe_raw(lcm_t *lcm, const char *channel, lcm_msg_handler_t handler, void *user)
{
    return rx_subscribe_raw_where(lcm, channel, NULL, 0, 0, handler, user);
}

/* Through liblcm: its subscription, behind the filter on its socket. */
static int subscribe_liblcm(lcm_t *lcm, rx_raw_t *r)
{
    auv_chanfilter_t *f = auv_chanfilter_of(lcm);
    const auv_chanfilter_rule_t rule = {r->pattern, r->payload, r->payload_at, r->payload_len};
    if (auv_chanfilter_note_rule(f, &rule) < 0)
        return -1;
    r->lcm_sub = lcm_subscribe(lcm, r->pattern, r->fn, r->user);
    if (r->lcm_sub && auv_chanfilter_apply(f) < 0) {
        static int told;
        if (!told++)
            fprintf(stderr, "lcm_rx: the kernel refused the channel filter (%s): this process receives every channel\n",
                    strerror(errno));
    }
    return r->lcm_sub ? 0 : -1;
}

rx_raw_t *rx_subscribe_raw_where(lcm_t *lcm, const char *channel, const void *payload, int payload_at,
                                 int payload_len, lcm_msg_handler_t handler, void *user)
{
    if (!lcm || !channel || !handler || payload_len < 0 || (payload_len > 0 && !payload))
        return NULL;
    rx_raw_t *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->fn = handler;
    r->user = user;
    r->pattern = strdup(channel);
    r->payload_at = payload_at;
    r->payload_len = payload_len;
    if (payload_len > 0 && (r->payload = malloc((size_t)payload_len)))
        memcpy(r->payload, payload, (size_t)payload_len);
    rx_own_t *own = rx_own_of(lcm);
    int ok = r->pattern && (payload_len == 0 || r->payload) &&
             (own ? rx_own_add(own, r) == 0 : subscribe_liblcm(lcm, r) == 0);
    if (!ok) {
        free(r->pattern);
        free(r->payload);
        free(r);
        return NULL;
    }
    return r;
}

void rx_unsubscribe_raw(lcm_t *lcm, rx_raw_t *r)
{
    if (!r)
        return;
    if (r->own) {
        rx_own_remove(r->own, r); /* frees it, or after the dispatch in progress */
        return;
    }
    if (r->lcm_sub)
        lcm_unsubscribe(lcm, r->lcm_sub);
    else
        regfree(&r->re); /* an own-socket route whose instance is gone */
    free(r->pattern);
    free(r->payload);
    free(r);
}

int rx_raw_set_queue_capacity(rx_raw_t *r, int capacity)
{
    /* on an own socket nothing queues in the process: the kernel's receive
     * buffer is the queue, and the url's recv_buf_size sizes it */
    return r->lcm_sub ? lcm_subscription_set_queue_capacity(r->lcm_sub, capacity) : 0;
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
        s->route = rx_subscribe_raw(lcm, channel, on_message, s);
    if (!s->route) {
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
    rx_unsubscribe_raw(lcm, sub->route);
    free(sub->scratch);
    free(sub);
}

int rx_set_queue_capacity(rx_sub_t *sub, int capacity)
{
    return rx_raw_set_queue_capacity(sub->route, capacity);
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
