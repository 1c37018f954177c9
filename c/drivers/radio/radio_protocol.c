/* auv-radio's protocol (radio.h): the radio's frames in and out, the status
 * home at the surface, the managers' answers relayed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_chasm_status_t.h"
#include "auv/auv_mission_ack_t.h"
#include "auv/auv_modem_rx_t.h"
#include "auv/auv_modem_tx_t.h"
#include "auv/auv_nav_solution_t.h"
#include "auv/auv_radio_ack_t.h"
#include "auv/auv_radio_chunk_t.h"
#include "auv/auv_radio_frame_t.h"
#include "auv/auv_radio_report_t.h"
#include "common/lcm_rx.h"
#include "drivers/radio/radio.h"

#define SHORE "SHORE"

void radio_send(radio_state *s, const uint8_t *payload, int len, int64_t now)
{
    radio_send_to(s, SHORE, payload, len, now);
}

void radio_send_to(radio_state *s, const char *dst, const uint8_t *payload, int len, int64_t now)
{
    auv_radio_frame_t f = {.utime = now, .src = (char *)s->ctx->vehicle, .dst = (char *)dst, .seq = ++s->seq,
                           .n_bytes = len, .payload = (uint8_t *)payload};
    int n = auv_radio_frame_t_encoded_size(&f);
    uint8_t *frame = malloc((size_t)n), *out = malloc((size_t)n + RP_OVERHEAD);
    size_t k = 0;
    if (frame && out && auv_radio_frame_t_encode(frame, 0, n, &f) == n)
        k = rp_encode(frame, (size_t)n, out, (size_t)n + RP_OVERHEAD);
    /* a pipe that will not take it (down, or full) loses it, as the air would: the protocol resends */
    if (!k || drv_write(s->ctx, out, k) != 0)
        s->frames_unsent++;
    free(frame);
    free(out);
}

/* An encoded message of the given type to the shore. */
#define SEND(TYPE, s, msg, now)                                                   \
    do {                                                                          \
        int n_ = TYPE##_encoded_size(msg);                                        \
        uint8_t *b_ = malloc((size_t)n_);                                         \
        if (b_ && TYPE##_encode(b_, 0, n_, msg) == n_)                            \
            radio_send((s), b_, n_, (now));                                       \
        free(b_);                                                                 \
    } while (0)

static void on_chunk(radio_state *s, const auv_radio_chunk_t *c, int64_t now)
{
    ra_offer o;
    if (!s->spool_open) {
        drv_drop(s->ctx, "no spool", "chunk %d of transfer %lld", (int)c->index, (long long)c->transfer_id);
        return;
    }
    ra_offer_chunk(&s->asm_, s->ctx, c, (double)now * 1e-6, &o);
    if (o.data) { /* verified whole: handed on exactly as the operator's tool encoded it */
        const auv_type_entry_t *type =
            auv_type_find(!strcmp(o.channel, "MISSION_CMD") ? "mission_command_t" : "plugin_upload_t");
        drv_publish_encoded(s->ctx, o.channel, type, o.data, (int)o.len);
        s->delivered++;
    }
    auv_radio_ack_t ack = {.utime = now, .transfer_id = c->transfer_id, .vehicle = (char *)s->ctx->vehicle,
                           .next_index = o.next_index, .state = (int8_t)o.state, .reason = o.reason};
    SEND(auv_radio_ack_t, s, &ack, now);
    ra_offer_free(&o);
}

/* One frame out of the pipe: a chunk for this vehicle, or dropped. */
static void on_frame(void *user, const uint8_t *bytes, size_t n)
{
    radio_state *s = user;
    int64_t now = s->stamp; /* the read's */
    auv_radio_frame_t f;
    if (rx_decode(auv_type_find("radio_frame_t"), bytes, (int)n, &f) != 0) {
        s->frames_dropped++;
        drv_drop(s->ctx, "undecodable frame", "%zu bytes with a good CRC", n);
        return;
    }
    if (!strcmp(f.dst, s->ctx->vehicle) && strcmp(f.src, SHORE)) { /* a teammate's: never a command */
        radio_peers_heard(s, f.src, f.payload, f.n_bytes, now);
        auv_radio_frame_t_decode_cleanup(&f);
        return;
    }
    auv_radio_chunk_t c;
    int is_chunk = rx_decode(auv_type_find("radio_chunk_t"), f.payload, f.n_bytes, &c) == 0;
    if (!is_chunk || strcmp(f.dst, s->ctx->vehicle)) {
        s->frames_dropped++;
        drv_drop(s->ctx, is_chunk ? "another node's frame" : "not a chunk", "from %.32s to %.32s", f.src, f.dst);
    } else {
        drv_frame_ok(s->ctx, now);
        on_chunk(s, &c, now);
    }
    if (is_chunk)
        auv_radio_chunk_t_decode_cleanup(&c);
    auv_radio_frame_t_decode_cleanup(&f);
}

static void radio_feed(void *st, drv_ctx *ctx, const uint8_t *bytes, size_t n, int64_t stamp)
{
    radio_state *s = st;
    s->stamp = stamp;
    rp_feed(&s->pipe, ctx, bytes, n, on_frame, s);
}

static int at_surface(const radio_state *s) { return s->have_nav && s->depth < s->surface_depth_m; }

static void report(radio_state *s, int64_t now)
{
    int64_t ids[RA_MAX_TRANSFERS];
    int32_t next[RA_MAX_TRANSFERS];
    int n = s->spool_open ? ra_holding(&s->asm_, ids, next, RA_MAX_TRANSFERS) : 0;
    auv_radio_report_t r = {.utime = now, .vehicle = (char *)s->ctx->vehicle, .mission = s->mission,
                            .contacts = s->contacts, .n_transfers = (int16_t)n, .transfer_id = ids,
                            .next_index = next,
                            .refused = (int32_t)(s->asm_.refused + s->acoustic_refused)};
    if (s->have_nav) {
        r.latitude_deg = s->lat;
        r.longitude_deg = s->lon;
        r.north_m = s->north;
        r.east_m = s->east;
        r.depth_m = s->depth;
        r.nav_status = s->nav_status;
        r.nav_utime = s->nav_utime;
    }
    int len = auv_radio_report_t_encoded_size(&r);
    uint8_t *b = malloc((size_t)len);
    if (b && auv_radio_report_t_encode(b, 0, len, &r) == len) {
        radio_send(s, b, len, now);
        radio_peers_send(s, b, len, now); /* and to the teammates in range */
    }
    free(b);
}

static void radio_tick(void *st, drv_ctx *ctx, int64_t now)
{
    (void)ctx;
    radio_state *s = st;
    if (s->spool_open)
        ra_expire(&s->asm_, s->ctx, (double)now * 1e-6);
    if (now < s->next_report_us || !at_surface(s))
        return;
    s->next_report_us = now + (int64_t)llround(s->report_period_s * 1e6);
    report(s, now);
    int kept = 0;
    for (int i = 0; i < s->n_acks; i++) { /* the managers' answers, each at RADIO_ACK_SENDS reports */
        radio_ack_slot *a = &s->acks[i];
        radio_send(s, a->data, a->len, now);
        if (--a->sends_left > 0)
            s->acks[kept++] = *a;
    }
    s->n_acks = kept;
}

/* ------------------------------------------------------------ LCM inputs */
static void on_nav(void *st, drv_ctx *ctx, const void *msg, int64_t now)
{
    (void)ctx, (void)now;
    radio_state *s = st;
    const auv_nav_solution_t *m = msg;
    s->have_nav = 1;
    s->lat = m->latitude_deg;
    s->lon = m->longitude_deg;
    s->north = m->north_m;
    s->east = m->east_m;
    s->depth = m->depth_m;
    s->nav_status = m->status;
    s->nav_utime = m->utime;
}

static void on_status(void *st, drv_ctx *ctx, const void *msg, int64_t now)
{
    (void)ctx, (void)now;
    static const char *const RUN[] = {"LOADING", "RUNNING", "PAUSED", "DONE", "ABORTED", "FAILED"};
    radio_state *s = st;
    const auv_chasm_status_t *m = msg;
    size_t k = (size_t)snprintf(s->mission, sizeof s->mission, "%s ",
                                m->run_state >= 0 && m->run_state <= 5 ? RUN[m->run_state] : "?");
    for (int i = 0; i < m->path_len && k < sizeof s->mission; i++)
        k += (size_t)snprintf(s->mission + k, sizeof s->mission - k, "%s%s", i ? "/" : "", m->active_path[i]);
}

static void on_ack(void *st, drv_ctx *ctx, const void *msg, int64_t now)
{
    (void)now;
    radio_state *s = st;
    const auv_mission_ack_t *m = msg;
    int n = auv_mission_ack_t_encoded_size(m);
    if (n > RADIO_ACK_BYTES) {
        drv_drop(ctx, "answer too long", "a mission_ack_t of %d bytes", n);
        return;
    }
    if (s->n_acks == RADIO_MAX_ACKS) { /* the oldest goes */
        memmove(s->acks, s->acks + 1, (RADIO_MAX_ACKS - 1) * sizeof s->acks[0]);
        s->n_acks--;
    }
    radio_ack_slot *a = &s->acks[s->n_acks];
    if (auv_mission_ack_t_encode(a->data, 0, n, m) != n)
        return;
    a->len = n;
    a->sends_left = RADIO_ACK_SENDS;
    s->n_acks++;
}

static void on_contact(void *st, drv_ctx *ctx, const void *msg, int64_t now)
{
    (void)ctx, (void)msg, (void)now;
    ((radio_state *)st)->contacts++;
}

static void on_modem(void *st, drv_ctx *ctx, const void *msg, int64_t now)
{
    (void)ctx;
    const auv_modem_rx_t *m = msg;
    if (m->kind == AUV_MODEM_TX_T_KIND_TEAM)
        radio_acoustic_heard(st, m->payload, m->n_bytes, now);
}

static const drv_subscription radio_subscriptions[] = {
    {"NAV", "nav_solution_t", on_nav},
    {radio_chasm_suffix, "chasm_status_t", on_status},
    {"MISSION_ACK", "mission_ack_t", on_ack},
    {"CONTACTS", "sidescan_contact_t", on_contact},
    {"MODEM_RX", "modem_rx_t", on_modem},
    {0},
};

/* ------------------------------------------------------------ life */
static int radio_init(void *st, drv_ctx *ctx)
{
    radio_state *s = st;
    s->ctx = ctx;
    if (!(s->given & RADIO_GIVEN_TEAM))
        s->team_index = -1;
    if (!(s->given & RADIO_GIVEN_SURFACE))
        s->surface_depth_m = 0.5;
    if (!(s->given & RADIO_GIVEN_REPORT))
        s->report_period_s = 2.0;
    if (!(s->given & RADIO_GIVEN_EXPIRY))
        s->idle_expiry_s = 3600.0;
    if (!s->spool) {
        if (ctx->write) { /* the driver itself: where would a transfer survive a restart? */
            drv_log(ctx, "--spool DIR is required");
            return -1;
        }
        return 0; /* the replay and the fuzzers: frames are decoded, chunks refused */
    }
    char err[600];
    if (ra_open(&s->asm_, ctx, ctx->vehicle, s->spool, s->idle_expiry_s, err, sizeof err) < 0) {
        drv_log(ctx, "%s", err);
        return -1;
    }
    s->spool_open = 1;
    return radio_acoustic_init(s);
}

static void radio_opened(void *st, drv_ctx *ctx)
{
    radio_state *s = st;
    if (!s->ready_said) { /* subscribed and the pipe open: what comes from now on is heard */
        printf("%s: ready\n", ctx->program);
        fflush(stdout);
        s->ready_said = 1;
    }
}

static void radio_reset(void *st, drv_ctx *ctx)
{
    (void)ctx;
    rp_reset(&((radio_state *)st)->pipe);
}

static void radio_finish(void *st, drv_ctx *ctx, int64_t now)
{
    (void)now;
    radio_state *s = st;
    char refused[1024] = "";
    size_t k = 0;
    for (int i = 0; i < ctx->reasons.n && k < sizeof refused; i++)
        k += (size_t)snprintf(refused + k, sizeof refused - k, "%s%s %lld", k ? ", " : "", ctx->reasons.name[i],
                              (long long)ctx->reasons.count[i]);
    fprintf(stderr, "auv-radio %s: delivered %lld, acoustic commands %lld, frames dropped %lld, unsent %lld, "
                    "peer reports %lld, refused: %s\n",
            ctx->vehicle, (long long)s->delivered, (long long)s->acoustic_commands, (long long)s->frames_dropped,
            (long long)s->frames_unsent, (long long)s->peer_reports, k ? refused : "none");
    if (s->have_ring)
        auth_keys_clear(&s->ring);
}

const drv_protocol radio_protocol = {
    .device = "RADIO",
    .program = "auv-radio",
    .summary = "The vehicle's end of the surface radio (docs/radio.md): chunks of operator commands in from a "
               "radio modem's byte pipe, assembled in --spool and published whole on <V>.MISSION_CMD or "
               "<V>.PLUGIN_UPLOAD once their SHA-256 checks; the status home and the managers' answers out at "
               "the surface; the shore's acoustic commands (<V>.MODEM_RX) issued to the managers.",
    .default_baud = 115200,
    .state_size = sizeof(radio_state),
    .flags = radio_flags,
    .subscriptions = radio_subscriptions,
    .link_time = 0,
    .init = radio_init,
    .feed = radio_feed,
    .tick = radio_tick,
    .opened = radio_opened,
    .reset = radio_reset,
    .finish = radio_finish,
};
DRV_REGISTER(radio_protocol)
