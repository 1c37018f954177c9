/* Message variables: a `messages` variable is a stream, a ring of the newest
 * `capacity` messages (byte blobs) numbered by a sequence that never goes
 * back. Readers (actions, the host) each keep their own place (a sequence
 * number): each sees every message once, and one that falls more than
 * `capacity` behind loses the oldest (counted as missed). Posts of a cycle
 * wait in a queue of `capacity` entries and enter the ring when the cycle
 * ends, in order, so they are visible from the next cycle on. */
#ifndef CM_STREAM_H
#define CM_STREAM_H
#include <stddef.h>
#include <stdint.h>

#define CM_STREAM_DEFAULT_CAPACITY CHASM_MESSAGES_DEFAULT_CAPACITY
#define CM_STREAM_MAX_CAPACITY CHASM_MESSAGES_MAX_CAPACITY

typedef struct {
    unsigned char *data;
    size_t len, cap;   /* cap: bytes allocated; grows to the largest message held */
} cm_blob;

typedef struct cm_stream {
    struct cm_var *var;
    uint32_t capacity;
    cm_blob *ring;                  /* message n is at ring[n % capacity] */
    uint64_t head;                  /* sequence number of the next message */
    cm_blob *pending;               /* posts of this cycle, capacity entries */
    uint32_t n_pending;
    uint64_t cycle_first;           /* first message visible for the first time this cycle */
    uint64_t seen_head;             /* head when the current cycle began */
    uint64_t host_next;             /* the host's place (chasm_messages_take) */
    uint64_t missed, refused;
    struct cm_stream *next;
} cm_stream;

struct chasm_machine;
struct cm_var;
/* A stream for v (malloc'd, freed by cm_streams_free). NULL: out of memory. */
cm_stream *cm_stream_new(struct chasm_machine *m, struct cm_var *v, uint32_t capacity);
void cm_streams_free(struct chasm_machine *m);
/* Begins a cycle: what arrived since the last one becomes "this cycle's". */
void cm_streams_begin_cycle(struct chasm_machine *m);
/* Ends a cycle: queued posts enter their rings, stamped now. */
void cm_streams_commit(struct chasm_machine *m, int64_t now);
/* The message after *next (oldest still held if *next fell behind: the
 * skipped ones are added to the stream's missed count); NULL when none. */
const void *cm_stream_next(cm_stream *s, uint64_t *next, size_t *len);
/* Queues a post; 0, or -1 (refused and counted: too large, queue full, no memory). */
int cm_stream_post(cm_stream *s, const void *data, size_t len);
#endif
