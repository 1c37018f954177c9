/* The recorder's event queue: the LCM handler puts each received message
 * here and returns at once; the writer thread takes them to disk. Bounded by
 * bytes, not messages: when full, the newest message is dropped and counted
 * (never silently, never blocking reception). */
#ifndef REC_QUEUE_H
#define REC_QUEUE_H

#include <pthread.h>
#include <stdint.h>
#include <stddef.h>

typedef struct rec_event {
    struct rec_event *next;
    int64_t timestamp;          /* receive time [us since epoch], as lcm-logger */
    int32_t channellen;
    int32_t datalen;
    char bytes[];               /* channel (no NUL) then data */
} rec_event;

typedef struct {
    pthread_mutex_t mu;
    pthread_cond_t cv;          /* the queue passed wake_bytes, a drain is wanted, or it closed */
    pthread_cond_t drained;     /* the writer took events out */
    rec_event *head, *tail;
    size_t bytes, capacity;     /* queued bytes, limit */
    size_t high_water;          /* most bytes ever queued */
    size_t wake_bytes;          /* the writer is woken early past this many queued bytes */
    int drain_wanted;           /* someone waits in rec_queue_wait_below */
    int64_t pushed, dropped;
    int closed;
} rec_queue;

int rec_queue_init(rec_queue *q, size_t capacity_bytes);
void rec_queue_destroy(rec_queue *q);
/* 0 queued, -1 dropped (queue full or out of memory; counted). */
int rec_queue_push(rec_queue *q, int64_t timestamp, const char *channel, const void *data, int32_t datalen);
/* Every queued event as a list (oldest first), after waiting up to
 * timeout_ms for the queue to pass wake_bytes (or to close, or for a drain to
 * be wanted): the writer takes events in batches instead of waking for each
 * one. NULL when nothing is queued. Caller frees each with free(). */
rec_event *rec_queue_take_all(rec_queue *q, int timeout_ms, int *closed);
/* No more pushes; the writer drains what is left, then sees closed. */
void rec_queue_close(rec_queue *q);
size_t rec_queue_bytes(rec_queue *q);
/* Wait (up to timeout_ms) until at most `bytes` are queued; 1 if so. */
int rec_queue_wait_below(rec_queue *q, size_t bytes, int timeout_ms);
int64_t rec_queue_dropped(rec_queue *q);

#endif
