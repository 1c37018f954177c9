#include "tm_outbox.h"

#include <string.h>

void tm_outbox_init(tm_outbox *o, int repeat)
{
    memset(o, 0, sizeof *o);
    o->repeat = repeat > 0 ? repeat : 1;
}

void tm_outbox_ack(tm_outbox *o, int to, int number)
{
    for (int i = 0; i < o->n_acks; i++)
        if (o->acks[i].to == to && o->acks[i].number == number)
            return;   /* already waiting for the next frame */
    if (o->n_acks >= TM_MAX_ACKS) {
        o->acks_dropped++;   /* the reporter repeats; it will be acked then */
        return;
    }
    o->acks[o->n_acks++] = (tm_ack){to, number};
}

int tm_outbox_ident(tm_outbox *o)
{
    if (o->n_idents >= TM_MAX_IDENTS)
        return -1;
    o->ident_sends[o->n_idents] = 0;
    return o->n_idents++;
}

void tm_outbox_contact(tm_outbox *o, int number)
{
    for (int i = 0; i < o->n_contacts; i++)
        if (o->contacts[i].number == number)
            return;
    if (o->n_contacts < TM_MAX_OUT_CONTACTS)
        o->contacts[o->n_contacts++] = (tm_out_contact){number, 0, 0, 0};
}

int tm_outbox_acked(tm_outbox *o, int number)
{
    for (int i = 0; i < o->n_contacts; i++)
        if (o->contacts[i].number == number) {
            int was = o->contacts[i].acked;
            o->contacts[i].acked = 1;
            return !was;
        }
    return 0;
}

void tm_outbox_status(tm_outbox *o) { o->status_pending = 1; }

void tm_outbox_front(tm_outbox *o) { o->front_pending = 1; }

int tm_outbox_unacked(const tm_outbox *o)
{
    int k = 0;
    for (int i = 0; i < o->n_contacts; i++)
        k += !o->contacts[i].acked && !o->contacts[i].refused;
    return k;
}

typedef struct {
    const tm_frame_writer *w;
    tm_item *put;
    int max, n;
    long *refused;
} filler;

/* 1 appended, 0 not, -1 refused (counted) */
static int offer(filler *f, tm_item it)
{
    if (f->n >= f->max)
        return 0;
    int r = f->w->put(f->w->user, &it);
    if (r > 0)
        f->put[f->n++] = it;
    else if (r < 0)
        (*f->refused)++;
    return r;
}

/* Contacts eligible in this band (early: sent < repeat), fewest sends first,
 * then the oldest; each at most once per frame. */
static void offer_contacts(tm_outbox *o, filler *f, int late, unsigned char *done)
{
    for (;;) {
        int best = -1;
        for (int i = 0; i < o->n_contacts; i++) {
            tm_out_contact *c = &o->contacts[i];
            if (done[i] || c->acked || c->refused || (c->sends >= o->repeat) != late)
                continue;
            if (best < 0 || c->sends < o->contacts[best].sends)
                best = i;
        }
        if (best < 0)
            return;
        done[best] = 1;
        int r = offer(f, (tm_item){TM_ITEM_CONTACT, o->contacts[best].number, 0});
        if (r > 0)
            o->contacts[best].sends++;
        else if (r < 0)
            o->contacts[best].refused = 1;
    }
}

int tm_outbox_fill(tm_outbox *o, const tm_frame_writer *w, tm_item *put, int max)
{
    filler f = {w, put, max, 0, &o->refused};
    /* 1. acks: each offered once; one that does not fit waits for the next frame */
    int kept = 0;
    for (int i = 0; i < o->n_acks; i++) {
        int r = offer(&f, (tm_item){TM_ITEM_ACK, o->acks[i].to, o->acks[i].number});
        if (r == 0)
            o->acks[kept++] = o->acks[i];
    }
    o->n_acks = kept;
    /* 2. idents */
    for (int i = 0; i < o->n_idents; i++) {
        if (o->ident_sends[i] >= o->repeat)
            continue;
        int r = offer(&f, (tm_item){TM_ITEM_IDENT, i, 0});
        if (r != 0)
            o->ident_sends[i] = r > 0 ? o->ident_sends[i] + 1 : o->repeat;
    }
    /* 3.-5. contacts around the status */
    unsigned char done[TM_MAX_OUT_CONTACTS] = {0};
    offer_contacts(o, &f, 0, done);
    if (o->status_pending && offer(&f, (tm_item){TM_ITEM_STATUS, 0, 0}) != 0)
        o->status_pending = 0;
    offer_contacts(o, &f, 1, done);
    /* 6. the own front summary (sampling): the newest only, once; a frame
     * without room for it leaves it for the next, unless a newer one came */
    if (o->front_pending && offer(&f, (tm_item){TM_ITEM_FRONT, 0, 0}) != 0)
        o->front_pending = 0;
    if (f.n > 0)
        o->frames++;
    return f.n;
}
