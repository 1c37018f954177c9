/* SPSC message FIFO: see msg_queue.h.
 *
 * head counts pushes (written by the producer only), tail counts pops
 * (consumer only); slot i % n holds message i. A slot's buffer belongs to the
 * producer while i >= tail + n would hold, to the consumer once head > i:
 * the release store of head / tail hands it over, so the buffers need no
 * lock. The mutex and condition variables are only for sleeping.
 *
 * Sleeping without lost wake-ups: the sleeper stores its `waiting` flag, then
 * re-reads the counter it waits on, under the mutex; the other side stores
 * the counter, then reads the flag, and signals under the same mutex. Both
 * pairs are sequentially consistent, so at least one of the two sees the
 * other's store: either the sleeper does not sleep, or it is signalled.
 */
#include "sender/msg_queue.h"

#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* After its spin, a consumer with a busy producer dozes in sleeps of
 * DOZE_STEP_NS for up to DOZE_NS before it sleeps until woken. */
#define DOZE_STEP_NS 50000L
#define DOZE_NS 20000000u

typedef struct {
    char *buf;          /* channel, NUL, data */
    size_t cap;
    size_t chan_len;
    uint32_t len;
} slot_t;

struct msg_queue {
    slot_t *slots;
    size_t n;
    uint64_t spin_ns;
    _Atomic uint64_t head;
    _Atomic uint64_t tail;
    _Atomic int closed;
    _Atomic int producer_idle;  /* set by flush(), cleared by push(): no spinning then */
    _Atomic int consumer_waiting;
    _Atomic int producer_waiting;
    pthread_mutex_t mu;
    pthread_cond_t consumer_cv;
    pthread_cond_t producer_cv;
    _Atomic uint64_t full_waits;
    _Atomic uint64_t consumer_sleeps;
    _Atomic uint64_t flushes;
};

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* One turn of a spin: give the core away if another thread wants it. On an
 * idle machine this returns at once; on a busy one the thread we wait for
 * (or any other) runs instead of our spinning. */
static void cpu_relax(void)
{
    sched_yield();
}

msg_queue_t *msg_queue_create(size_t slots, uint32_t spin_ns)
{
    if (slots == 0)
        return NULL;
    msg_queue_t *q = calloc(1, sizeof *q);
    if (!q)
        return NULL;
    q->slots = calloc(slots, sizeof *q->slots);
    if (!q->slots) {
        free(q);
        return NULL;
    }
    q->n = slots;
    q->spin_ns = spin_ns;
    atomic_init(&q->head, 0);
    atomic_init(&q->tail, 0);
    atomic_init(&q->closed, 0);
    atomic_init(&q->producer_idle, 0);
    atomic_init(&q->consumer_waiting, 0);
    atomic_init(&q->producer_waiting, 0);
    atomic_init(&q->full_waits, 0);
    atomic_init(&q->consumer_sleeps, 0);
    atomic_init(&q->flushes, 0);
    pthread_mutex_init(&q->mu, NULL);
    pthread_cond_init(&q->consumer_cv, NULL);
    pthread_cond_init(&q->producer_cv, NULL);
    return q;
}

void msg_queue_destroy(msg_queue_t *q)
{
    if (!q)
        return;
    for (size_t i = 0; i < q->n; i++)
        free(q->slots[i].buf);
    free(q->slots);
    pthread_mutex_destroy(&q->mu);
    pthread_cond_destroy(&q->consumer_cv);
    pthread_cond_destroy(&q->producer_cv);
    free(q);
}

/* Producer: wait until tail >= target (spin, then sleep). */
static void wait_tail(msg_queue_t *q, uint64_t target)
{
    uint64_t deadline = now_ns() + q->spin_ns;
    while (atomic_load(&q->tail) < target) {
        if (now_ns() >= deadline) {
            pthread_mutex_lock(&q->mu);
            atomic_store(&q->producer_waiting, 1);
            while (atomic_load(&q->tail) < target)
                pthread_cond_wait(&q->producer_cv, &q->mu);
            atomic_store(&q->producer_waiting, 0);
            pthread_mutex_unlock(&q->mu);
            return;
        }
        cpu_relax();
    }
}

static void wake(msg_queue_t *q, _Atomic int *waiting, pthread_cond_t *cv)
{
    if (atomic_load(waiting)) {
        pthread_mutex_lock(&q->mu);
        pthread_cond_signal(cv);
        pthread_mutex_unlock(&q->mu);
    }
}

int msg_queue_push(msg_queue_t *q, const char *channel, const void *data, uint32_t len)
{
    if (atomic_load_explicit(&q->closed, memory_order_relaxed))
        return -1;
    uint64_t h = atomic_load_explicit(&q->head, memory_order_relaxed);
    if (h - atomic_load(&q->tail) >= q->n) {
        atomic_fetch_add_explicit(&q->full_waits, 1, memory_order_relaxed);
        wait_tail(q, h - q->n + 1);
    }
    slot_t *s = &q->slots[h % q->n];
    size_t chan_len = strlen(channel);
    size_t need = chan_len + 1 + (size_t)len;
    if (need > s->cap) {
        char *nb = realloc(s->buf, need);
        if (!nb)
            return -1;
        s->buf = nb;
        s->cap = need;
    }
    memcpy(s->buf, channel, chan_len + 1);
    if (len)
        memcpy(s->buf + chan_len + 1, data, len);
    s->chan_len = chan_len;
    s->len = len;
    atomic_store_explicit(&q->producer_idle, 0, memory_order_relaxed);
    atomic_store(&q->head, h + 1);
    wake(q, &q->consumer_waiting, &q->consumer_cv);
    return 0;
}

void msg_queue_flush(msg_queue_t *q)
{
    atomic_fetch_add_explicit(&q->flushes, 1, memory_order_relaxed);
    /* the producer is about to wait for something else: once this is sent,
     * nothing more comes soon, so the consumer need not spin for it */
    atomic_store_explicit(&q->producer_idle, 1, memory_order_relaxed);
    wait_tail(q, atomic_load_explicit(&q->head, memory_order_relaxed));
}

void msg_queue_close(msg_queue_t *q)
{
    atomic_store(&q->closed, 1);
    pthread_mutex_lock(&q->mu);
    pthread_cond_signal(&q->consumer_cv);
    pthread_mutex_unlock(&q->mu);
}

uint64_t msg_queue_pending(const msg_queue_t *q)
{
    uint64_t t = atomic_load(&((msg_queue_t *)q)->tail);
    return atomic_load(&((msg_queue_t *)q)->head) - t;
}

/* Consumer: is there a message at t, or nothing more to come? */
static int ready(msg_queue_t *q, uint64_t t)
{
    return atomic_load(&q->head) != t || atomic_load(&q->closed);
}

/* Consumer: wait for a message at t (or the end) without the producer's help
 * while it is busy: spin, then doze in short sleeps, so that its push never
 * has to wake us (a wake-up costs the producer 10 us to milliseconds on a
 * busy virtual machine). False if it is time to sleep until woken: the
 * producer said it is idle (flush), or nothing came for DOZE_NS. */
static int wait_unaided(msg_queue_t *q, uint64_t t)
{
    if (atomic_load_explicit(&q->producer_idle, memory_order_relaxed))
        return 0;
    uint64_t start = now_ns();
    while (!ready(q, t)) {
        uint64_t now = now_ns();
        if (now - start < q->spin_ns) {
            cpu_relax();
            continue;
        }
        if (now - start >= DOZE_NS || atomic_load_explicit(&q->producer_idle, memory_order_relaxed))
            return 0;
        struct timespec ts = {0, DOZE_STEP_NS};
        nanosleep(&ts, NULL);
    }
    return 1;
}

int msg_queue_peek(msg_queue_t *q, const char **channel, const void **data, uint32_t *len)
{
    uint64_t t = atomic_load_explicit(&q->tail, memory_order_relaxed);
    if (!ready(q, t) && !wait_unaided(q, t)) {
        pthread_mutex_lock(&q->mu);
        atomic_store(&q->consumer_waiting, 1);
        if (!ready(q, t))
            atomic_fetch_add_explicit(&q->consumer_sleeps, 1, memory_order_relaxed);
        while (!ready(q, t))
            pthread_cond_wait(&q->consumer_cv, &q->mu);
        atomic_store(&q->consumer_waiting, 0);
        pthread_mutex_unlock(&q->mu);
    }
    if (atomic_load(&q->head) == t)
        return 1; /* closed, and everything pushed was popped */
    const slot_t *s = &q->slots[t % q->n];
    *channel = s->buf;
    *data = s->buf + s->chan_len + 1;
    *len = s->len;
    return 0;
}

void msg_queue_pop(msg_queue_t *q)
{
    atomic_store(&q->tail, atomic_load_explicit(&q->tail, memory_order_relaxed) + 1);
    wake(q, &q->producer_waiting, &q->producer_cv);
}

void msg_queue_get_stats(const msg_queue_t *q, msg_queue_stats_t *out)
{
    msg_queue_t *m = (msg_queue_t *)q;
    out->popped = atomic_load(&m->tail);
    out->pushed = atomic_load(&m->head);
    out->full_waits = atomic_load(&m->full_waits);
    out->consumer_sleeps = atomic_load(&m->consumer_sleeps);
    out->flushes = atomic_load(&m->flushes);
}
