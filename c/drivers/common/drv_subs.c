#include "drivers/common/drv_subs.h"

#include <stdio.h>
#include <string.h>

static void on_msg(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)recv_utime; /* the driver stamps with its own clock, as it stamps bytes */
    drv_sub_binding *b = user;
    drv_subs *s = b->owner;
    int64_t now = drv_clock_now(s->clock);
    if (now < 0) {
        /* with --clock sim a command before the first SIM.CLOCK cannot be
         * judged by the time rule: refused, as unstamped bytes are */
        drv_drop(s->ctx, "no clock yet", "a %s on %s before the first SIM.CLOCK", b->spec->type_name, channel);
        return;
    }
    b->spec->handler(s->state, s->ctx, msg, now);
}

int drv_subs_init(drv_subs *s, lcm_t *lcm, const drv_protocol *p, void *state, drv_ctx *ctx, const drv_clock *clock,
                  char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    s->state = state;
    s->ctx = ctx;
    s->clock = clock;
    for (const drv_subscription *e = p->subscriptions; e && e->suffix; e++) {
        if (s->n == DRV_MAX_SUBS) {
            snprintf(err, errlen, "more than %d subscriptions", DRV_MAX_SUBS);
            return -1;
        }
        const auv_type_entry_t *type = auv_type_find(e->type_name);
        if (!type || !e->handler) {
            snprintf(err, errlen, "subscription %s: %s", e->suffix,
                     type ? "no handler" : "no such message type");
            return -1;
        }
        drv_sub_binding *b = &s->b[s->n];
        b->spec = e;
        b->owner = s;
        snprintf(b->channel, sizeof b->channel, "%s.%s", ctx->vehicle, e->suffix);
        snprintf(b->reason, sizeof b->reason, "undecodable %s", e->suffix);
        b->sub = rx_subscribe(lcm, b->channel, type, on_msg, b);
        if (!b->sub) {
            snprintf(err, errlen, "cannot subscribe to %s", b->channel);
            return -1;
        }
        s->n++;
    }
    return 0;
}

void drv_subs_account(drv_subs *s)
{
    for (int i = 0; i < s->n; i++) {
        drv_sub_binding *b = &s->b[i];
        const rx_stats_t *st = rx_stats(b->sub);
        while (b->errors_counted < rx_decode_errors(b->sub)) {
            b->errors_counted++;
            drv_drop(s->ctx, b->reason, "%s: %llu wrong type, %llu malformed, as %s", b->channel,
                     (unsigned long long)st->wrong_fingerprint, (unsigned long long)st->malformed,
                     b->spec->type_name);
        }
    }
}

void drv_subs_close(drv_subs *s, lcm_t *lcm)
{
    for (int i = 0; i < s->n; i++)
        rx_unsubscribe(lcm, s->b[i].sub);
    s->n = 0;
}
