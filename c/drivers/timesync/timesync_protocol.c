/* auv-timesync's protocol: $PAUVT sentences (pauvt.c) through the time rule
 * into SIM.CLOCK (timesync.h). */
#include <stdio.h>
#include <string.h>

#include "auv/auv_sim_clock_t.h"
#include "drivers/timesync/timesync.h"

static int timesync_init(void *state, drv_ctx *ctx)
{
    timesync_state *s = state;
    nmea_framer_init(&s->framer, 0);
    tp_clock_init(&s->clock, TP_MAX_CLOCK_JUMP_US);
    snprintf(s->server_id, sizeof s->server_id, "%s-timelink", ctx->vehicle);
    s->clock_type = auv_type_find("sim_clock_t");
    if (!s->clock_type) {
        drv_log(ctx, "sim_clock_t is not in the type table");
        return -1;
    }
    return 0;
}

static void publish_clock(timesync_state *s, drv_ctx *ctx, const pauvt_values *v)
{
    auv_sim_clock_t m;
    memset(&m, 0, sizeof m);
    m.utime = v->utime;
    m.server_id = s->server_id;
    m.term = 0; /* one link, no election: every follower's term check passes */
    /* the managers and auv-nav pace nothing by mode or warp (they cycle on
     * each accepted utime); both are for whoever shows or logs the clock */
    m.mode = v->warp == 1.0 ? AUV_SIM_CLOCK_T_MODE_REALTIME : AUV_SIM_CLOCK_T_MODE_SCALED;
    m.warp = v->warp;
    drv_publish_global(ctx, "SIM.CLOCK", s->clock_type, &m);
}

static void on_sentence(timesync_state *s, drv_ctx *ctx, int64_t stamp)
{
    pauvt_values v;
    char why[200];
    const char *reason = pauvt_decode(&s->sentence, &v, why, sizeof why);
    if (reason) {
        drv_drop(ctx, reason, "%s", why);
        return;
    }
    /* the rule every follower applies again: what passes here passes there,
     * and a follower started later sees no step back either */
    tp_reason r = tp_clock_offer(&s->clock, v.utime);
    if (r != TP_OK) {
        drv_drop(ctx, tp_reason_name(r), "%lld us after %lld us", (long long)v.utime, (long long)s->clock.now);
        return;
    }
    drv_frame_ok(ctx, stamp);
    publish_clock(s, ctx, &v);
}

static void timesync_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    timesync_state *s = state;
    for (size_t i = 0; i < n; i++) {
        int r = nmea_framer_push(&s->framer, bytes[i], &s->sentence);
        if (r == NMEA_OK)
            on_sentence(s, ctx, stamp);
        else if (r > 0)
            drv_drop(ctx, nmea_result_name((nmea_result)r), "%.*s", (int)(s->framer.len < 60 ? s->framer.len : 60),
                     s->framer.buf);
        /* garbage between sentences: one count per run, as every NMEA driver */
        if (s->framer.garbage_bytes != s->garbage_seen) {
            s->garbage_seen = s->framer.garbage_bytes;
            if (!s->in_garbage)
                drv_drop(ctx, "garbage", "bytes outside any sentence, from 0x%02x", bytes[i]);
            s->in_garbage = 1;
        } else if (s->framer.in_sentence) {
            s->in_garbage = 0;
        }
    }
}

static void timesync_reset(void *state, drv_ctx *ctx)
{
    timesync_state *s = state;
    (void)ctx;
    /* a half sentence never ends; the clock's time rule stays: the link's
     * time after a reconnection is judged against the time before */
    nmea_framer_init(&s->framer, 0);
    s->garbage_seen = 0;
    s->in_garbage = 0;
}

const drv_protocol timesync_protocol = {
    .device = "TIMESYNC",
    .program = "auv-timesync",
    .summary = "The time link of hardware in the loop at the wire: $PAUVT,<sim time us>,<warp>*hh sentences\n"
               "from the simulator, each the sim time of its own last byte, into SIM.CLOCK (sim_clock_t) on\n"
               "this LCM, after the time rule (never backwards, a jump confirmed by a second sentence).\n"
               "It is the clock source: it runs on the system clock (--clock sim is refused).",
    .default_baud = 115200,
    .state_size = sizeof(timesync_state),
    .link_time = 1,
    .clock_source = 1,
    .init = timesync_init,
    .feed = timesync_feed,
    .reset = timesync_reset,
};

DRV_REGISTER(timesync_protocol)
