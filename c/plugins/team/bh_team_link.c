/* team_link: the team's acoustic link and this vehicle's team identity.
 *
 *   team_link(team = "AUV1,AUV2,AUV3,AUV4", me = "AUV2", my_slot = 1)
 *
 * Every cycle it applies each received KIND_TEAM frame (modem_rx_t messages)
 * to the store: peer statuses, contact reports (acked when this vehicle runs
 * ri_reacquire), acks of own contacts, identification results. A teammate is
 * lost when its status says abort or nothing was heard from it for `silent`
 * (PEER_LOST); one whose last status said done is finished, and its silence
 * is no loss. In its TDMA slot (tm_tdma.h) it sends one frame of at most
 * frame_bytes, filled by priority (tm_outbox.h), as a modem_tx_t KIND_TEAM.
 * With `front` bound (a sampling plan: <V>.FRONT_ESTIMATE, the vehicle's own
 * fit) it also sends the newest OK estimate as the link's front summary,
 * once, after the status (teamlink/team_front.h): what teammates' estimators
 * fit as a prior (docs/sampling.md).
 * It is also the one writer of the events output: it posts the events every
 * team behavior queued (team_event_t). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_front_estimate_t.h"
#include "auv/auv_modem_rx_t.h"
#include "auv/auv_modem_tx_t.h"
#include "auv/auv_team_event_t.h"
#include "tm_behaviors.h"
#include "tm_frame.h"
#include "tm_store.h"
#include "tm_tdma.h"
#include "teamlink/team_front.h"

const chasm_param_spec tm_link_params[LINK_NPARAMS] = {
    [LINK_TEAM] = CHASM_PARAM_REQUIRED_STRING(
        "team", "the roster, the same in every plan: \"AUV1,AUV2,AUV3,AUV4\" (index = team number)"),
    [LINK_ME] = CHASM_PARAM_REQUIRED_STRING("me", "this vehicle's name in the roster"),
    [LINK_SLOT] = CHASM_PARAM_DOUBLE_RANGE("slot", "s", 5, 0.1, 600, "TDMA slot length"),
    [LINK_SLOTS] = CHASM_PARAM_INT_RANGE("slots", 4, 1, 16, "slots in a TDMA round"),
    [LINK_MY_SLOT] = CHASM_PARAM_INT_RANGE("my_slot", 0, 0, 15, "this vehicle's slot (0 .. slots - 1)"),
    [LINK_WINDOW] = CHASM_PARAM_DOUBLE_RANGE("window", "s", 1, 0.01, 600,
                                             "a frame starts only this soon after the slot's start"),
    [LINK_FRAME_BYTES] = CHASM_PARAM_INT_RANGE("frame_bytes", 32, 4, 256, "the modem's frame size"),
    [LINK_SILENT] = CHASM_PARAM_DOUBLE_RANGE("silent", "s", 120, 1, 36000,
                                             "a teammate not heard for this long is lost"),
    [LINK_REPEAT] = CHASM_PARAM_INT_RANGE("repeat", 3, 1, 100,
                                          "sends of an unacked contact before it yields to the status (it is still "
                                          "resent until acked); sends of each ident"),
    [LINK_RX] = CHASM_READ("rx", CHASM_MESSAGES, "", "modem_rx",
                           "frames received (messages bound to <V>.MODEM_RX modem_rx_t)"),
    [LINK_TX] = CHASM_WRITE("tx", CHASM_MESSAGES, "", "modem_tx",
                            "frames to send (messages bound to <V>.MODEM_TX modem_tx_t)"),
    [LINK_EVENTS] = CHASM_WRITE("events", CHASM_MESSAGES, "", "team_events",
                                "team events (messages bound to <V>.TEAM_EVENT team_event_t)"),
    [LINK_FRONT] = CHASM_READ("front", CHASM_MESSAGES, "", "",
                              "optional: the vehicle's own front estimates (messages bound to <V>.FRONT_ESTIMATE "
                              "front_estimate_t), sent to the team as the link's front summary"),
};
_Static_assert(CHASM_COUNT(tm_link_params) == LINK_NPARAMS, "team_link schema and slots disagree");

typedef struct {
    tm_tdma tdma;
    long refused_logged, bad_logged;   /* counts already reported in the log */
    long unsendable_logged;
} link_state;
_Static_assert(sizeof(link_state) <= 64, "team_link state size in the descriptor");

int tm_link_start(chasm_ctx *c, void *state)
{
    link_state *ls = state;
    tm_roster r;
    char why[160];
    if (tm_roster_parse(&r, chasm_param_string(c, LINK_TEAM), why, sizeof why)) {
        char msg[240];
        snprintf(msg, sizeof msg, "team_link: team: %s", why);
        chasm_log(c, msg);
        return -1;
    }
    int me = tm_roster_index(&r, chasm_param_string(c, LINK_ME));
    if (me < 0) {
        chasm_log(c, "team_link: me is not in the team roster");
        return -1;
    }
    tm_store_configure(tm_store_get(), &r, me, c->now_us, (int)chasm_param_int(c, LINK_REPEAT));
    tm_tdma_init(&ls->tdma, chasm_param_double(c, LINK_SLOT), (int)chasm_param_int(c, LINK_SLOTS),
                 (int)chasm_param_int(c, LINK_MY_SLOT), chasm_param_double(c, LINK_WINDOW));
    return 0;
}

static void receive(chasm_ctx *c, tm_store *s)
{
    const void *msg;
    size_t len;
    while ((msg = chasm_next_message(c, LINK_RX, &len))) {
        auv_modem_rx_t f;
        if (len > 1u << 20 || auv_modem_rx_t_decode(msg, 0, (int)len, &f) < 0) {
            s->undecodable++;
            continue;
        }
        int src = tm_roster_index(&s->roster, f.src_vehicle ? f.src_vehicle : "");
        if (f.kind != 2 /* KIND_TEAM */ || src < 0 || src == s->me || f.n_bytes < 0) {
            s->frames_foreign++;
        } else {
            s->frames_in++;
            tm_peer *p = &s->peer[src];
            p->heard = 1;
            p->t_heard = (double)c->now_us * 1e-6;
            tm_frame_receive(s, src, f.payload, (size_t)f.n_bytes, c->now_us);
        }
        auv_modem_rx_t_decode_cleanup(&f);
    }
}

/* The newest of this cycle's own front estimates, as the summary to send. */
static void take_front(chasm_ctx *c, tm_store *s, link_state *ls)
{
    const void *msg;
    size_t len;
    while ((msg = chasm_next_message(c, LINK_FRONT, &len))) {
        auv_front_estimate_t f;
        if (len > 1u << 16 || auv_front_estimate_t_decode(msg, 0, (int)len, &f) < 0) {
            s->undecodable++;
            continue;
        }
        if (f.status == AUV_FRONT_ESTIMATE_T_STATUS_OK && f.vehicle && !strcmp(f.vehicle, s->roster.name[s->me])) {
            team_front_estimate e = {s->me,          (double)f.utime * 1e-6, f.offset_m,
                                     f.angle_rad,    f.temperature_a_c,      f.temperature_b_c,
                                     f.width_m,      f.offset_sigma_m,       f.angle_sigma_rad,
                                     f.temperature_a_sigma_c, f.temperature_b_sigma_c, f.width_sigma_m,
                                     f.samples_used};
            team_msg_front m;
            if (team_front_summary(&e, &m)) {
                s->own_front = m;
                s->has_own_front = 1;
                s->fronts_made++;
                tm_outbox_front(&s->out);
            } else {
                s->fronts_not_sendable++;
            }
        }
        auv_front_estimate_t_decode_cleanup(&f);
    }
    if (s->fronts_not_sendable != ls->unsendable_logged) {
        char text[200];
        snprintf(text, sizeof text,
                 "team_link: %ld front estimates not sent so far: outside the summary's ranges (a sigma over "
                 "25.5 m or 0.255 rad, a width over 409.5 m)", s->fronts_not_sendable);
        chasm_log(c, text);
        ls->unsendable_logged = s->fronts_not_sendable;
    }
}

static void watch_peers(chasm_ctx *c, tm_store *s)
{
    double now = (double)c->now_us * 1e-6, silent = chasm_param_double(c, LINK_SILENT);
    for (int v = 0; v < s->roster.n; v++) {
        tm_peer *p = &s->peer[v];
        if (v == s->me || p->lost)
            continue;
        if (p->has_status && p->state == TM_ST_DONE)
            continue;   /* finished: its link ends with its mission, silence is no loss */
        double quiet = now - (p->heard ? p->t_heard : s->t_start);
        int aborted = p->has_status && p->state == TM_ST_ABORT;
        if (aborted || quiet > silent) {
            p->lost = 1;
            char text[80];
            snprintf(text, sizeof text, aborted ? "aborted" : "silent for %.0f s", quiet);
            tm_post(s, c->now_us, TM_EV_PEER_LOST, v, -1, p->track.n, p->track.e, 0, text);
        }
    }
}

static void send(chasm_ctx *c, tm_store *s, link_state *ls)
{
    int64_t round = tm_tdma_may_send(&ls->tdma, c->now_us);
    if (round < 0)
        return;
    tm_tdma_sent(&ls->tdma, round);
    uint8_t frame[256];
    tm_item items[64];
    int n;
    size_t bytes = tm_frame_build(s, c->now_us, frame, (size_t)chasm_param_int(c, LINK_FRAME_BYTES), items, 64, &n);
    if (s->out.refused != ls->refused_logged) {
        char msg[200];
        snprintf(msg, sizeof msg,
                 "team_link: %ld messages refused by the link codec so far (a value outside the schema's "
                 "range, c/plugins/team/team_link.schema)", s->out.refused);
        chasm_log(c, msg);
        ls->refused_logged = s->out.refused;
    }
    if (!bytes)
        return;
    auv_modem_tx_t tx = {0};
    tx.utime = c->now_us;
    tx.vehicle = s->roster.name[s->me];
    tx.dst_vehicle = "";
    tx.seq = s->seq++;
    tx.kind = 2; /* KIND_TEAM */
    tx.n_bytes = (int16_t)bytes;
    tx.payload = frame;
    uint8_t buf[512];
    int len = auv_modem_tx_t_encode(buf, 0, (int)sizeof buf, &tx);
    if (len < 0 || chasm_post_message(c, LINK_TX, buf, (size_t)len) < 0)
        return;
    s->frames_sent++;
    for (int i = 0; i < n; i++)
        if (items[i].kind == TM_ITEM_FRONT)
            s->fronts_sent++;
    for (int i = 0; i < n; i++)
        if (items[i].kind == TM_ITEM_CONTACT) {
            const tm_contact *k = &s->contacts.c[items[i].a];
            int sends = 0;
            for (int j = 0; j < s->out.n_contacts; j++)
                if (s->out.contacts[j].number == k->number)
                    sends = s->out.contacts[j].sends;
            char text[32];
            snprintf(text, sizeof text, "send %d", sends);
            tm_post(s, c->now_us, TM_EV_CONTACT_SENT, s->me, k->number, k->n, k->e, 0, text);
        }
}

static void post_events(chasm_ctx *c, tm_store *s)
{
    for (int i = 0; i < s->n_events; i++) {
        const tm_event *v = &s->events[i];
        auv_team_event_t ev = {0};
        ev.utime = v->utime;
        ev.vehicle = s->roster.name[s->me];
        ev.kind = (int8_t)v->kind;
        ev.origin = (char *)tm_name(s, v->origin);
        ev.number = v->number;
        ev.north_m = v->n;
        ev.east_m = v->e;
        ev.result = (int8_t)v->result;
        ev.text = (char *)v->text;
        uint8_t buf[512];
        int len = auv_team_event_t_encode(buf, 0, (int)sizeof buf, &ev);
        if (len < 0 || chasm_post_message(c, LINK_EVENTS, buf, (size_t)len) < 0)
            s->events_dropped++;
    }
    s->n_events = 0;
}

chasm_status_code tm_link_step(chasm_ctx *c, void *state)
{
    tm_store *s = tm_store_get();
    s->last_now_us = c->now_us;
    link_state *ls = state;
    receive(c, s);
    if (s->frames_bad + s->undecodable != ls->bad_logged) {
        char msg[160];
        snprintf(msg, sizeof msg, "team_link: %ld frames and %ld input messages did not decode so far", s->frames_bad,
                 s->undecodable);
        chasm_log(c, msg);
        ls->bad_logged = s->frames_bad + s->undecodable;
    }
    watch_peers(c, s);
    take_front(c, s, ls);
    send(c, s, ls);
    post_events(c, s);
    return CHASM_RUNNING;
}
