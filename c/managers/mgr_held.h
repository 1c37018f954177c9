/* Inputs that arrived before their step's clock, held until it has passed.
 *
 * In lockstep a manager's cycle at clock t_k works on what the steps before
 * k published (docs/scenarios.md, "Overload slows time"): everything stamped
 * up to t_{k-1}. Whoever publishes in step k does so after hearing clock k,
 * but the kernel hands one multicast datagram to its member sockets one
 * after the other: a fast reader (another manager, a simulator) can hear
 * clock k, run and publish, and have its message of step k reach this
 * socket before clock k itself does. Applied on arrival, that message would
 * be in this manager's cycle k in one run and not in the next (measured: 2
 * of 140 000 messages of a loaded demo reached the recorder ahead of their
 * clock). So, in lockstep, an input stamped after the manager's current
 * clock waits here, as received, and is applied after the cycle of the
 * first clock that is not before its stamp: where it lands when it arrives
 * in order. */
#ifndef MGR_HELD_H
#define MGR_HELD_H

#include <stddef.h>
#include <stdint.h>

/* At most this many messages wait at once; past it, one is applied on
 * arrival (as without holding) and counted: a step's own traffic for one
 * manager is a handful of messages, so this only bounds a flood. */
#define MGR_HELD_MAX 4096

typedef struct mgr_held_msg {
    void *binding;          /* the input binding it arrived on */
    int64_t utime;          /* its stamp */
    size_t len;
    unsigned char *data;    /* the encoded message, as received */
} mgr_held_msg;

typedef struct {
    mgr_held_msg *items;    /* in arrival order */
    size_t n, cap;
    uint64_t held;          /* messages that waited for their clock */
    uint64_t overflow;      /* applied on arrival because the queue was full */
} mgr_held;

/* Keep a copy of one message; 0, or -1 when full or out of memory. */
int mgr_held_push(mgr_held *h, void *binding, int64_t utime, const void *data, size_t len);

/* Hand every message stamped at or before now to apply, in arrival order,
 * and forget it; a message still ahead of now keeps its place. */
typedef void (*mgr_held_apply)(void *binding, int64_t utime, const void *data, size_t len, void *user);
void mgr_held_release(mgr_held *h, int64_t now, mgr_held_apply apply, void *user);

void mgr_held_free(mgr_held *h);

#endif
