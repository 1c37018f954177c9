/* An LCM publisher with its own thread: publish() queues, the thread sends.
 *
 * Why: a process that subscribes on a udpm URL receives its own multicast
 * packets, so every lcm_publish() also wakes liblcm's receive thread; on a
 * virtual machine with an idle second core that wake-up costs the publishing
 * thread tens of microseconds, as much as a physics step of the simulator.
 * Here the publishing thread only copies the message into a FIFO
 * (msg_queue.h); a sender thread with its own publish-only lcm_t (which has
 * no receive socket) calls lcm_publish in the same order. Nothing is dropped:
 * a full queue makes publish() wait. flush() returns once every message
 * published so far has been handed to the kernel.
 *
 * Loaded from Python with ctypes (python/auvlcm/sender.py): plain C types
 * only, no Python headers.
 */
#ifndef AUV_LCM_SENDER_H
#define AUV_LCM_SENDER_H

#include <stdint.h>

typedef struct auv_lcm_sender auv_lcm_sender_t;

typedef struct {
    uint64_t published;       /* messages accepted by publish() */
    uint64_t sent;            /* messages lcm_publish() was called for */
    uint64_t send_errors;     /* of those, how many lcm_publish() refused */
    uint64_t full_waits;      /* publish() calls that waited for a full queue */
    uint64_t sender_sleeps;   /* times the sender thread slept on an empty queue */
    uint64_t flushes;
} auv_lcm_sender_stats_t;

/* url: an LCM URL; slots: messages in flight (>= 1); spin_us: how long either
 * thread spins before it sleeps. NULL on error (bad URL, no memory, no thread). */
auv_lcm_sender_t *auv_lcm_sender_create(const char *url, uint32_t slots, uint32_t spin_us);
/* Queue one message (copied); 0, or -1 after close or out of memory. */
int auv_lcm_sender_publish(auv_lcm_sender_t *s, const char *channel, const void *data,
                           uint32_t len);
/* Wait until every message published so far has been sent. */
void auv_lcm_sender_flush(auv_lcm_sender_t *s);
/* Messages published and not yet sent. */
uint64_t auv_lcm_sender_pending(const auv_lcm_sender_t *s);
void auv_lcm_sender_get_stats(const auv_lcm_sender_t *s, auv_lcm_sender_stats_t *out);
/* errno-style code of the last failed send (0 if none). */
int auv_lcm_sender_last_error(const auv_lcm_sender_t *s);
/* Send what is queued, stop the thread, free everything. */
void auv_lcm_sender_destroy(auv_lcm_sender_t *s);

#endif
