/* A single-producer single-consumer FIFO of (channel, bytes) messages.
 *
 * Why: the simulator's loop hands each message to a sender thread instead of
 * calling lcm_publish itself (see lcm_sender.h). The queue keeps the order,
 * never drops: a push into a full queue waits for a free slot, and counts it.
 *
 * Waking a sleeping thread costs the waker tens of microseconds on a virtual
 * machine (milliseconds when the host is busy): more than the work between
 * two messages when the loop runs fast. So a consumer with an empty queue
 * spins for `spin_ns`, then dozes in short sleeps for up to 20 ms, and only
 * then sleeps on a condition variable, the one state a push must wake it
 * from (a pusher signals only then). After a flush() the consumer sleeps at
 * once: the producer said it is about to wait for something else, so a loop
 * paced by a clock costs no spinning between its bursts. A producer waiting
 * for a full queue or a flush spins for `spin_ns`, then sleeps.
 *
 * One thread may push/flush, one other thread may peek/pop. close() may be
 * called by the producer once it has pushed its last message.
 */
#ifndef AUV_MSG_QUEUE_H
#define AUV_MSG_QUEUE_H

#include <stddef.h>
#include <stdint.h>

typedef struct msg_queue msg_queue_t;

typedef struct {
    uint64_t pushed;          /* messages accepted by push() */
    uint64_t popped;          /* messages released by pop() */
    uint64_t full_waits;      /* pushes that found the queue full and waited */
    uint64_t consumer_sleeps; /* times the consumer went to sleep on an empty queue */
    uint64_t flushes;         /* flush() calls */
} msg_queue_stats_t;

/* slots >= 1 messages in flight; NULL if out of memory. */
msg_queue_t *msg_queue_create(size_t slots, uint32_t spin_ns);
void msg_queue_destroy(msg_queue_t *q);

/* Producer: copy one message in; waits while the queue is full.
 * 0 on success, -1 if the queue is closed or memory ran out. */
int msg_queue_push(msg_queue_t *q, const char *channel, const void *data, uint32_t len);
/* Producer: wait until every message pushed so far has been popped. */
void msg_queue_flush(msg_queue_t *q);
/* Producer: no more pushes; the consumer drains what is queued, then peek() returns 1. */
void msg_queue_close(msg_queue_t *q);
/* Messages pushed but not yet popped (either side, a snapshot). */
uint64_t msg_queue_pending(const msg_queue_t *q);

/* Consumer: wait for the oldest message and point at it (valid until pop()).
 * 0 with a message, 1 when the queue is closed and empty. */
int msg_queue_peek(msg_queue_t *q, const char **channel, const void **data, uint32_t *len);
/* Consumer: release the message peek() returned. */
void msg_queue_pop(msg_queue_t *q);

void msg_queue_get_stats(const msg_queue_t *q, msg_queue_stats_t *out);

#endif
