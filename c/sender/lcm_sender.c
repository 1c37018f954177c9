/* LCM publisher thread: see lcm_sender.h. */
#define _GNU_SOURCE /* pthread_setname_np: the thread shows as lcm-sender in top -H */
#include "sender/lcm_sender.h"

#include <errno.h>
#include <lcm/lcm.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>

#include "sender/msg_queue.h"

struct auv_lcm_sender {
    lcm_t *lcm;
    msg_queue_t *q;
    pthread_t thread;
    _Atomic uint64_t sent;
    _Atomic uint64_t send_errors;
    _Atomic int last_error;
};

static void *send_loop(void *arg)
{
    auv_lcm_sender_t *s = arg;
    pthread_setname_np(pthread_self(), "lcm-sender");
    const char *channel;
    const void *data;
    uint32_t len;
    while (msg_queue_peek(s->q, &channel, &data, &len) == 0) {
        errno = 0;
        if (lcm_publish(s->lcm, channel, data, len) != 0) {
            atomic_fetch_add(&s->send_errors, 1);
            atomic_store(&s->last_error, errno ? errno : EIO);
        }
        atomic_fetch_add(&s->sent, 1);
        msg_queue_pop(s->q);
    }
    return NULL;
}

auv_lcm_sender_t *auv_lcm_sender_create(const char *url, uint32_t slots, uint32_t spin_us)
{
    auv_lcm_sender_t *s = calloc(1, sizeof *s);
    if (!s)
        return NULL;
    atomic_init(&s->sent, 0);
    atomic_init(&s->send_errors, 0);
    atomic_init(&s->last_error, 0);
    s->lcm = lcm_create(url);
    s->q = msg_queue_create(slots, spin_us * 1000u);
    if (!s->lcm || !s->q)
        goto fail;
    /* The sender takes no signals: they belong to the process's main thread
     * (Python runs its handlers there), and none may interrupt a send. */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    int rc = pthread_create(&s->thread, NULL, send_loop, s);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (rc != 0)
        goto fail;
    return s;
fail:
    if (s->q)
        msg_queue_destroy(s->q);
    if (s->lcm)
        lcm_destroy(s->lcm);
    free(s);
    return NULL;
}

int auv_lcm_sender_publish(auv_lcm_sender_t *s, const char *channel, const void *data,
                           uint32_t len)
{
    return msg_queue_push(s->q, channel, data, len);
}

void auv_lcm_sender_flush(auv_lcm_sender_t *s)
{
    msg_queue_flush(s->q);
}

uint64_t auv_lcm_sender_pending(const auv_lcm_sender_t *s)
{
    return msg_queue_pending(s->q);
}

void auv_lcm_sender_get_stats(const auv_lcm_sender_t *s, auv_lcm_sender_stats_t *out)
{
    msg_queue_stats_t qs;
    msg_queue_get_stats(s->q, &qs);
    auv_lcm_sender_t *m = (auv_lcm_sender_t *)s;
    out->published = qs.pushed;
    out->sent = atomic_load(&m->sent);
    out->send_errors = atomic_load(&m->send_errors);
    out->full_waits = qs.full_waits;
    out->sender_sleeps = qs.consumer_sleeps;
    out->flushes = qs.flushes;
}

int auv_lcm_sender_last_error(const auv_lcm_sender_t *s)
{
    return atomic_load(&((auv_lcm_sender_t *)s)->last_error);
}

void auv_lcm_sender_destroy(auv_lcm_sender_t *s)
{
    if (!s)
        return;
    msg_queue_close(s->q);
    pthread_join(s->thread, NULL);
    msg_queue_destroy(s->q);
    lcm_destroy(s->lcm);
    free(s);
}
