/* What this vehicle has to say, and the priority rule that fills one frame
 * per TDMA round with it.
 *
 * Priority, highest first:
 *   1. acks      each received contact report is acknowledged once (a repeat
 *                of a report means the last ack was lost, so it is acked again);
 *   2. idents    each identification result, sent `repeat` times (no ack);
 *   3. contacts  own mine-like contacts not yet acknowledged, fewest sends
 *                first, while sent fewer than `repeat` times;
 *   4. status    the newest own status;
 *   5. contacts  still unacknowledged after `repeat` sends: still resent every
 *                round until acknowledged, but behind the status, so a peer
 *                that lost the ack does not starve the team of positions.
 * Items are offered in that order to a frame writer that says whether each
 * fits; one that does not fit is skipped for a smaller later one. An item the
 * writer refuses (a value outside the schema's range) is dropped and counted. */
#ifndef TM_OUTBOX_H
#define TM_OUTBOX_H

#include "plugins/lib/pu_visibility.h"

#define TM_MAX_ACKS 64
#define TM_MAX_IDENTS 256
#define TM_MAX_OUT_CONTACTS 256

typedef enum { TM_ITEM_ACK = 1, TM_ITEM_IDENT = 2, TM_ITEM_CONTACT = 3, TM_ITEM_STATUS = 4, TM_ITEM_FRONT = 5 } tm_item_kind;

typedef struct {
    tm_item_kind kind;
    int a, b;    /* ack: to, number; ident: index in the ident list; contact: own number; status: - */
} tm_item;

/* Appends an item to the frame: 1 appended, 0 does not fit (frame unchanged),
 * -1 refused (cannot be encoded). */
typedef struct {
    int (*put)(void *user, const tm_item *it);
    void *user;
} tm_frame_writer;

typedef struct {
    int to, number;
} tm_ack;

typedef struct {
    int number;    /* own contact number */
    int sends;
    int acked;
    int refused;
} tm_out_contact;

typedef struct {
    tm_ack acks[TM_MAX_ACKS];
    int n_acks;
    int ident_sends[TM_MAX_IDENTS];   /* per ident (indexed like the store's list) */
    int n_idents;
    tm_out_contact contacts[TM_MAX_OUT_CONTACTS];
    int n_contacts;
    int status_pending;
    int front_pending;    /* a new own front summary waits (the store holds it) */
    int repeat;
    /* counters */
    long acks_dropped;    /* ack queue full */
    long refused;         /* items the encoder refused */
    long frames;
} tm_outbox;

PU_HIDDEN void tm_outbox_init(tm_outbox *o, int repeat);
PU_HIDDEN void tm_outbox_ack(tm_outbox *o, int to, int number);
/* A new ident (its index in the caller's list must be n_idents). */
PU_HIDDEN int tm_outbox_ident(tm_outbox *o);
PU_HIDDEN void tm_outbox_contact(tm_outbox *o, int number);
/* An ack for own contact `number` arrived: 1 if it was not acked before. */
PU_HIDDEN int tm_outbox_acked(tm_outbox *o, int number);
PU_HIDDEN void tm_outbox_status(tm_outbox *o);
/* A new own front summary is in the store: send it once, after the status. */
PU_HIDDEN void tm_outbox_front(tm_outbox *o);
/* Fills one frame; put[] receives the items appended, in order (up to max).
 * Returns their count. */
PU_HIDDEN int tm_outbox_fill(tm_outbox *o, const tm_frame_writer *w, tm_item *put, int max);
/* Contacts queued and not yet acknowledged. */
PU_HIDDEN int tm_outbox_unacked(const tm_outbox *o);

#endif
