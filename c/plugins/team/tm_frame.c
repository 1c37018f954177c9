#include "tm_frame.h"

#include <math.h>
#include <stdio.h>

#include "plugins/lib/pu_angle.h"
#include "team/team_codec.h"

#define TM_TIME_WRAP 16384   /* the schema's time_s: 14 bits */

static int32_t stamp(int64_t now_us) { return (int32_t)((now_us / 1000000) % TM_TIME_WRAP); }

double tm_time_unwrap(int time_s, double now_s)
{
    double back = fmod(floor(now_s) - time_s, TM_TIME_WRAP);
    if (back < 0)
        back += TM_TIME_WRAP;
    return floor(now_s) - back;
}

typedef struct {
    tm_store *s;
    int64_t now_us;
    team_bits w;
} writer;

static void fill_msg(const writer *f, const tm_item *it, team_msg *m)
{
    const tm_store *s = f->s;
    switch (it->kind) {
    case TM_ITEM_ACK:
        m->id = TEAM_MSG_ACK;
        m->u.ack = (team_msg_ack){it->a, it->b};
        break;
    case TM_ITEM_IDENT: {
        const tm_ident *d = &s->idents[it->a];
        m->id = TEAM_MSG_IDENT;
        m->u.ident = (team_msg_ident){d->key.origin, d->key.number, d->result, d->n, d->e,
                                      (int32_t)((int64_t)d->t % TM_TIME_WRAP)};
        break;
    }
    case TM_ITEM_CONTACT: {
        const tm_contact *k = &s->contacts.c[it->a];
        m->id = TEAM_MSG_CONTACT;
        /* looks saturate at 15 (the field means "15 or more") */
        m->u.contact = (team_msg_contact){s->me, k->number, k->n, k->e, k->sigma, k->score,
                                          k->looks > 15 ? 15 : k->looks, stamp(f->now_us)};
        break;
    }
    case TM_ITEM_STATUS: {
        m->id = TEAM_MSG_STATUS;
        /* The stamp is the frame's whole second, and the position must be
         * where the vehicle was then: team_status took it up to a TDMA round
         * earlier, so it is dead-reckoned to the stamp (a teammate that
         * dead-reckons on from a stale fix at a later stamp runs metres
         * behind the truth). At the surface nav may read a few cm above it:
         * that is depth 0; a vehicle does not move backwards over ground. */
        tm_track at = tm_track_advance(s->own, (double)(f->now_us / 1000000) - s->t_own);
        m->u.status = (team_msg_status){s->me,
                                        stamp(f->now_us),
                                        at.n,
                                        at.e,
                                        s->own_depth < 0 ? 0.0 : s->own_depth,
                                        pu_wrap_2pi(s->own.heading),
                                        s->own.speed < 0 ? 0.0 : s->own.speed,
                                        s->next_line < TM_ALL_DONE ? s->next_line : TM_ALL_DONE,
                                        s->status_state};
        break;
    }
    case TM_ITEM_FRONT:
        m->id = TEAM_MSG_FRONT;
        m->u.front = s->own_front;
        break;
    }
}

static int put(void *user, const tm_item *it)
{
    writer *f = user;
    team_msg m;
    fill_msg(f, it, &m);
    int r = team_msg_encode(&m, &f->w);
    return r == TEAM_OK ? 1 : r == TEAM_ERR_FULL ? 0 : -1;
}

size_t tm_frame_build(tm_store *s, int64_t now_us, uint8_t *buf, size_t cap, tm_item *items, int max_put, int *n_put)
{
    writer f = {s, now_us, {0}};
    team_bits_writer(&f.w, buf, cap);
    tm_frame_writer w = {put, &f};
    *n_put = tm_outbox_fill(&s->out, &w, items, max_put);
    return *n_put ? team_bits_bytes(&f.w) : 0;
}

static void on_contact(tm_store *s, const team_msg_contact *k, int64_t now_us)
{
    int created;
    tm_key key = {k->origin, k->number};
    int aliases = 0;
    for (int j = 0; j < s->targets.n; j++)
        aliases += s->targets.t[j].n_alias;
    int i = tm_targets_report(&s->targets, key, k->north_m, k->east_m, k->sigma_m, k->score,
                              (double)now_us * 1e-6, s->merge_m, &created);
    if (i < 0)
        return;
    if (s->is_ri)   /* every copy is acked: a repeat means the last ack was lost */
        tm_outbox_ack(&s->out, k->origin, k->number);
    int now_aliases = 0;
    for (int j = 0; j < s->targets.n; j++)
        now_aliases += s->targets.t[j].n_alias;
    if (created || now_aliases != aliases)
        s->targets_changed = 1;   /* a new target, or a merge that moved one */
    if (created && s->is_ri) {
        char text[48];
        snprintf(text, sizeof text, "score %.2f", k->score);
        tm_post(s, now_us, TM_EV_TARGET_QUEUED, k->origin, k->number, k->north_m, k->east_m, 0, text);
    }
}

static void on_ident(tm_store *s, const team_msg_ident *d, int64_t now_us)
{
    for (int i = 0; i < s->n_idents_heard; i++)
        if (s->idents_heard[i].origin == d->origin && s->idents_heard[i].number == d->number)
            return;   /* a repeat */
    if (s->n_idents_heard < TM_MAX_IDENTS)
        s->idents_heard[s->n_idents_heard++] = (tm_key){d->origin, d->number};
    tm_post(s, now_us, TM_EV_IDENT_HEARD, d->origin, d->number, d->north_m, d->east_m, d->result, NULL);
}

int tm_frame_receive(tm_store *s, int src, const uint8_t *buf, size_t len, int64_t now_us)
{
    team_bits r;
    team_bits_reader(&r, buf, len);
    double now = (double)now_us * 1e-6;
    int n = 0;
    for (;;) {
        team_msg m;
        int id = team_decode_next(&r, &m);
        if (id == 0)
            return n;
        if (id < 0) {
            s->frames_bad++;
            return -1;
        }
        n++;
        switch (id) {
        case TEAM_MSG_STATUS: {
            const team_msg_status *st = &m.u.status;
            int v = st->vehicle;
            if (v != src || v >= s->roster.n || v == s->me)
                break;   /* a status speaks for its sender only */
            tm_peer *p = &s->peer[v];
            p->has_status = 1;
            p->t_status = tm_time_unwrap(st->time_s, now);
            p->track = (tm_track){st->north_m, st->east_m, st->heading, st->speed};
            p->depth = st->depth_m;
            p->next_line = st->next_line;
            p->state = st->state;
            break;
        }
        case TEAM_MSG_CONTACT:
            if (m.u.contact.origin < s->roster.n && m.u.contact.origin != s->me)
                on_contact(s, &m.u.contact, now_us);
            break;
        case TEAM_MSG_ACK:
            if (m.u.ack.to == s->me && tm_outbox_acked(&s->out, m.u.ack.number)) {
                const tm_contact *k = m.u.ack.number < s->contacts.n ? &s->contacts.c[m.u.ack.number] : NULL;
                tm_post(s, now_us, TM_EV_CONTACT_ACKED, s->me, m.u.ack.number, k ? k->n : 0, k ? k->e : 0, 0,
                         tm_name(s, src));
            }
            break;
        case TEAM_MSG_IDENT:
            on_ident(s, &m.u.ident, now_us);
            break;
        case TEAM_MSG_FRONT:   /* auv-front-estimate fits them (its own reader of MODEM_RX) */
            s->fronts_heard++;
            break;
        }
    }
}
