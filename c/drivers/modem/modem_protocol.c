/* auv-modem's protocol: the NMEA framer, the Micro-Modem subset's parser and
 * the bridge (mm_msg.h, mm_bridge.h) at the framework's moments, as
 * tools/mm_cli.c drives them without a port. What the bridge produces goes
 * out here: its sentences to the modem (drv_write), its frames on MODEM_RX,
 * its counts on MODEM_STATUS; every refusal it counts is also a drop by
 * reason, so driver_status_t says why as the other drivers do. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "auv/auv_modem_rx_t.h"
#include "auv/auv_modem_status_t.h"
#include "auv/auv_modem_tx_t.h"
#include "drivers/modem/modem.h"

static int modem_init(void *state, drv_ctx *ctx)
{
    modem_state *s = state;
    if (!s->have_table) {
        /* without a device (the replay, the fuzzer) the table only names the
         * senders: this vehicle alone, at address 1, unless one is given */
        const char *why;
        char spec[MM_NAME_MAX + 8];
        snprintf(spec, sizeof spec, "%.*s=1", MM_NAME_MAX - 1, ctx->vehicle);
        if (ctx->write || mm_table_parse(&s->table, spec, &why) < 0) {
            drv_log(ctx, "--table ID=ADDR,... is required (the vehicles' modem addresses, docs/drivers.md)");
            return -1;
        }
    }
    mm_options o;
    mm_options_default(&o);
    o.vehicle = ctx->vehicle;
    o.rate = s->rate;
    o.ack = s->ack;
    o.cst = !s->no_cst;
    if (s->kind_given)
        o.kind = s->kind;
    if (s->answer_timeout_s > 0)
        o.answer_timeout_us = (int64_t)llround(s->answer_timeout_s * 1e6);
    if (s->ack_timeout_s > 0)
        o.ack_timeout_us = (int64_t)llround(s->ack_timeout_s * 1e6);
    if (s->rx_hold_s > 0)
        o.rx_hold_us = (int64_t)llround(s->rx_hold_s * 1e6);
    const char *why = "";
    if (mm_bridge_init(&s->bridge, &o, &s->table, &why) < 0) {
        drv_log(ctx, "%s (--vehicle %s, --table)", why, ctx->vehicle);
        return -1;
    }
    s->counted = s->bridge.status;
    nmea_framer_init(&s->framer, 0);
    s->rx_type = auv_type_find("modem_rx_t");
    s->status_type = auv_type_find("modem_status_t");
    if (!s->rx_type || !s->status_type) {
        drv_log(ctx, "modem_rx_t or modem_status_t is not in the type table");
        return -1;
    }
    return 0;
}

static void publish_status(modem_state *s, drv_ctx *ctx, int64_t now)
{
    const mm_status *st = &s->bridge.status;
    auv_modem_status_t m;
    memset(&m, 0, sizeof m);
    m.utime = now;
    m.vehicle = (char *)ctx->vehicle;
    m.sent = st->sent;
    m.refused_size = st->refused_size;
    m.refused_rate = st->refused_rate;
    m.refused_invalid = st->refused_invalid;
    m.received = st->received;
    m.lost = st->lost; /* CACST's bad frames: heard, not decoded */
    /* out_of_range, collided, deaf: a real modem cannot tell them from silence (0) */
    m.last_refused_seq = st->last_refused_seq;
    m.last_refusal = (char *)st->last_refusal;
    m.busy_until_utime = st->busy_until_utime;
    m.acked = st->acked;
    m.ack_timeouts = st->ack_timeouts;
    m.timeouts = st->timeouts;
    m.modem_errors = st->modem_errors;
    m.rx_dropped = st->rx_dropped;
    m.last_error = (char *)st->last_error;
    m.modem_address = st->address;
    m.rate = st->rate;
    m.heartbeat_utime = st->heartbeat_utime;
    m.revision = (char *)st->revision;
    drv_publish(ctx, "MODEM_STATUS", s->status_type, &m);
    s->next_status = now + MODEM_STATUS_PERIOD_US;
}

static void publish_frame(modem_state *s, drv_ctx *ctx, const mm_rx_frame *f)
{
    auv_modem_rx_t m;
    memset(&m, 0, sizeof m);
    m.utime = f->utime; /* the CARXD's receive time */
    m.vehicle = (char *)ctx->vehicle;
    m.src_vehicle = (char *)f->src_vehicle;
    m.dst_vehicle = (char *)f->dst_vehicle;
    m.seq = ++s->rx_seq;
    m.kind = (int8_t)f->kind;
    m.tx_utime = 0;   /* not on the wire */
    m.range_m = NAN;  /* nor this */
    m.snr_db = f->snr_db;
    m.n_bytes = (int16_t)f->n_bytes;
    m.payload = (uint8_t *)f->payload;
    drv_publish(ctx, "MODEM_RX", s->rx_type, &m);
}

/* One drop per count the bridge added since the last call, by reason; the
 * bridge's own text (last_refusal, last_error) is the detail. */
static void count_drops(modem_state *s, drv_ctx *ctx)
{
    const mm_status *st = &s->bridge.status;
    mm_status *c = &s->counted;
    const struct {
        int64_t now, *seen;
        const char *reason, *detail;
    } k[] = {
        {st->refused_size, &c->refused_size, "frame over the rate's size", st->last_refusal},
        {st->refused_rate, &c->refused_rate, "busy", st->last_refusal},
        {st->refused_invalid, &c->refused_invalid, "invalid frame", st->last_refusal},
        {st->rx_dropped, &c->rx_dropped, "received frame dropped", st->last_error},
        {st->modem_errors, &c->modem_errors, "modem error", st->last_error},
        {st->timeouts, &c->timeouts, "modem timeout", st->last_error},
        {st->ack_timeouts, &c->ack_timeouts, "ack timeout", st->last_error},
    };
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        for (; *k[i].seen < k[i].now; (*k[i].seen)++)
            drv_drop(ctx, k[i].reason, "%s", k[i].detail);
}

/* What the last bridge call produced: sentences to the modem, frames, status. */
static void flush_out(modem_state *s, drv_ctx *ctx, int64_t now)
{
    mm_out *o = &s->out;
    for (int i = 0; i < o->n_sentences; i++) {
        char line[NMEA_MAX_SENTENCE + 8];
        int n = nmea_format(line, sizeof line, o->sentence[i]);
        if (n > 0)
            drv_write(ctx, (const uint8_t *)line, (size_t)n);
    }
    for (int i = 0; i < o->n_frames; i++)
        publish_frame(s, ctx, &o->frame[i]);
    count_drops(s, ctx);
    if (o->status_changed)
        publish_status(s, ctx, now);
    mm_out_clear(o);
}

static void on_tx(void *state, drv_ctx *ctx, const void *msg, int64_t now)
{
    modem_state *s = state;
    const auv_modem_tx_t *m = msg;
    mm_out_clear(&s->out);
    if (m->vehicle[0] && strcmp(m->vehicle, ctx->vehicle)) {
        /* the bridge knows only its own vehicle's frames: a stray sender is
         * refused here, counted where the simulator's modem counts it */
        mm_status *st = &s->bridge.status;
        st->refused_invalid++;
        st->last_refused_seq = m->seq;
        snprintf(st->last_refusal, sizeof st->last_refusal, "vehicle '%.32s' is not this modem's vehicle '%.32s'",
                 m->vehicle, ctx->vehicle);
        s->out.status_changed = 1;
    } else {
        mm_bridge_send(&s->bridge, m->seq, m->dst_vehicle, m->kind, m->payload, m->n_bytes, now, &s->out);
    }
    flush_out(s, ctx, now);
}

static void modem_opened(void *state, drv_ctx *ctx)
{
    modem_state *s = state;
    /* its address and CACST again: a modem that was power-cycled forgot them */
    mm_out_clear(&s->out);
    mm_bridge_start(&s->bridge, 0, &s->out);
    s->out.status_changed = 0; /* the next tick publishes, on the clock */
    flush_out(s, ctx, 0);
}

static void on_sentence(modem_state *s, drv_ctx *ctx, int64_t stamp)
{
    mm_msg m;
    const char *why = "";
    int r = mm_parse(&s->sentence, &m, &why);
    if (r > 0)
        return; /* not in the subset (a CAMPC echo, a CATXF, another talker): the modem says much */
    if (r < 0) {
        drv_drop(ctx, why, "%.80s", s->sentence.text);
        return;
    }
    drv_frame_ok(ctx, stamp);
    mm_out_clear(&s->out);
    mm_bridge_input(&s->bridge, &m, stamp, &s->out);
    flush_out(s, ctx, stamp);
}

static void modem_feed(void *state, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    modem_state *s = state;
    for (size_t i = 0; i < n; i++) {
        int r = nmea_framer_push(&s->framer, bytes[i], &s->sentence);
        if (r == NMEA_OK)
            on_sentence(s, ctx, stamp);
        else if (r > 0)
            drv_drop(ctx, nmea_result_name((nmea_result)r), "%.*s", (int)(s->framer.len < 60 ? s->framer.len : 60),
                     s->framer.buf);
        /* garbage between sentences: one count per run of it, not per byte */
        if (s->framer.garbage_bytes != s->garbage_seen) {
            s->garbage_seen = s->framer.garbage_bytes;
            if (!s->in_garbage)
                drv_drop(ctx, "garbage", "bytes outside any sentence, from 0x%02x", bytes[i]);
            s->in_garbage = 1;
        } else if (r >= 0) { /* a line ended: the run of garbage before it is over */
            s->in_garbage = 0;
        }
    }
}

static void modem_tick(void *state, drv_ctx *ctx, int64_t now)
{
    modem_state *s = state;
    if (s->next_status - now > MODEM_STATUS_PERIOD_US) /* the system clock stepped back */
        s->next_status = now;
    mm_out_clear(&s->out);
    mm_bridge_tick(&s->bridge, now, &s->out);
    if (now >= s->next_status)
        s->out.status_changed = 1;
    flush_out(s, ctx, now);
}

static void modem_reset(void *state, drv_ctx *ctx)
{
    modem_state *s = state;
    (void)ctx;
    /* a half sentence of a lost stream never ends; the cycle under way is
     * the bridge's to time out (the modem may have sent it all the same) */
    nmea_framer_init(&s->framer, 0);
    s->garbage_seen = 0;
    s->in_garbage = 0;
}

static void modem_finish(void *state, drv_ctx *ctx, int64_t now)
{
    modem_state *s = state;
    /* frames still waiting for their CACST: delivered without the SNR */
    mm_out_clear(&s->out);
    mm_bridge_flush(&s->bridge, &s->out);
    flush_out(s, ctx, now);
}

static const drv_subscription modem_subscriptions[] = {
    {"MODEM_TX", "modem_tx_t", on_tx},
    {0},
};

const drv_protocol modem_protocol = {
    .device = "MODEM",
    .program = "auv-modem",
    .summary = "WHOI Micro-Modem (NMEA interface): each modem_tx_t of <ID>.MODEM_TX is sent as one packet\n"
               "of one frame (CCCYC, then CCTXD on the modem's CADRQ); each frame the modem prints (CARXD)\n"
               "is a modem_rx_t on <ID>.MODEM_RX, stamped with its receive time; modem_status_t on\n"
               "<ID>.MODEM_STATUS when a count changes and once a second. Addresses from --table.",
    .default_baud = 19200,
    .state_size = sizeof(modem_state),
    .flags = modem_flags,
    .subscriptions = modem_subscriptions,
    .init = modem_init,
    .feed = modem_feed,
    .tick = modem_tick,
    .opened = modem_opened,
    .reset = modem_reset,
    .finish = modem_finish,
};

DRV_REGISTER(modem_protocol)
