#include "recorder/rec_queue.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static void deadline_in(struct timespec *ts, int ms)
{
    clock_gettime(CLOCK_MONOTONIC, ts);
    ts->tv_sec += ms / 1000;
    ts->tv_nsec += (long)(ms % 1000) * 1000000L;
    if (ts->tv_nsec >= 1000000000L) {
        ts->tv_sec++;
        ts->tv_nsec -= 1000000000L;
    }
}

static int init_cond(pthread_cond_t *cv)
{
    pthread_condattr_t a;
    if (pthread_condattr_init(&a))
        return -1;
    pthread_condattr_setclock(&a, CLOCK_MONOTONIC);
    int rc = pthread_cond_init(cv, &a);
    pthread_condattr_destroy(&a);
    return rc ? -1 : 0;
}

int rec_queue_init(rec_queue *q, size_t capacity_bytes)
{
    memset(q, 0, sizeof *q);
    q->capacity = capacity_bytes;
    /* A wake-up per message was a third context switch for each datagram
     * (after liblcm's thread and the handler); batches by time or size cost
     * one per batch. Small enough that a burst never nears the capacity. */
    q->wake_bytes = capacity_bytes / 16 > 0 ? capacity_bytes / 16 : 1;
    if (pthread_mutex_init(&q->mu, NULL) || init_cond(&q->cv) || init_cond(&q->drained))
        return -1;
    return 0;
}

void rec_queue_destroy(rec_queue *q)
{
    rec_event *e = q->head;
    while (e) {
        rec_event *n = e->next;
        free(e);
        e = n;
    }
    pthread_mutex_destroy(&q->mu);
    pthread_cond_destroy(&q->cv);
    pthread_cond_destroy(&q->drained);
}

int rec_queue_push(rec_queue *q, int64_t timestamp, const char *channel, const void *data, int32_t datalen)
{
    size_t chlen = strlen(channel);
    size_t size = sizeof(rec_event) + chlen + (size_t)datalen;
    pthread_mutex_lock(&q->mu);
    if (q->closed || q->bytes + size > q->capacity) {
        q->dropped++;
        pthread_mutex_unlock(&q->mu);
        return -1;
    }
    q->bytes += size;           /* reserved before the copy, outside the lock */
    pthread_mutex_unlock(&q->mu);

    rec_event *e = malloc(size);
    if (e) {
        e->next = NULL;
        e->timestamp = timestamp;
        e->channellen = (int32_t)chlen;
        e->datalen = datalen;
        memcpy(e->bytes, channel, chlen);
        if (datalen > 0)
            memcpy(e->bytes + chlen, data, (size_t)datalen);
    }
    pthread_mutex_lock(&q->mu);
    if (!e) {
        q->bytes -= size;
        q->dropped++;
    } else {
        if (q->tail)
            q->tail->next = e;
        else
            q->head = e;
        q->tail = e;
        q->pushed++;
        if (q->bytes > q->high_water)
            q->high_water = q->bytes;
        if (q->bytes >= q->wake_bytes && q->bytes - size < q->wake_bytes)
            pthread_cond_signal(&q->cv);
    }
    pthread_mutex_unlock(&q->mu);
    return e ? 0 : -1;
}

rec_event *rec_queue_take_all(rec_queue *q, int timeout_ms, int *closed)
{
    struct timespec until;
    deadline_in(&until, timeout_ms);
    pthread_mutex_lock(&q->mu);
    while (q->bytes < q->wake_bytes && !q->closed && !(q->drain_wanted && q->head)) {
        if (pthread_cond_timedwait(&q->cv, &q->mu, &until) == ETIMEDOUT)
            break;
    }
    rec_event *list = q->head;
    for (rec_event *e = list; e; e = e->next)
        q->bytes -= sizeof(rec_event) + (size_t)e->channellen + (size_t)e->datalen;
    q->head = q->tail = NULL;
    *closed = q->closed;
    pthread_cond_broadcast(&q->drained);
    pthread_mutex_unlock(&q->mu);
    return list;
}

void rec_queue_close(rec_queue *q)
{
    pthread_mutex_lock(&q->mu);
    q->closed = 1;
    pthread_cond_broadcast(&q->cv);
    pthread_mutex_unlock(&q->mu);
}

size_t rec_queue_bytes(rec_queue *q)
{
    pthread_mutex_lock(&q->mu);
    size_t b = q->bytes;
    pthread_mutex_unlock(&q->mu);
    return b;
}

int rec_queue_wait_below(rec_queue *q, size_t bytes, int timeout_ms)
{
    struct timespec until;
    deadline_in(&until, timeout_ms);
    pthread_mutex_lock(&q->mu);
    while (q->bytes > bytes) {
        q->drain_wanted = 1;
        pthread_cond_signal(&q->cv);
        if (pthread_cond_timedwait(&q->drained, &q->mu, &until) == ETIMEDOUT)
            break;
    }
    q->drain_wanted = 0;
    int ok = q->bytes <= bytes;
    pthread_mutex_unlock(&q->mu);
    return ok;
}

int64_t rec_queue_dropped(rec_queue *q)
{
    pthread_mutex_lock(&q->mu);
    int64_t d = q->dropped;
    pthread_mutex_unlock(&q->mu);
    return d;
}
