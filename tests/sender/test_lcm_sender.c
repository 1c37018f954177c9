/* Tests of the message FIFO and the LCM sender thread (c/sender/).
 *
 *   test_lcm_sender queue          order, blocking when full, flush, close
 *   test_lcm_sender lcm URL        the sender over real LCM: all messages, in order
 *
 * Prints one line per check; exits non-zero on the first failure.
 */
#include <lcm/lcm.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sender/lcm_sender.h"
#include "sender/msg_queue.h"

#define CHECK(cond, ...)                                                   \
    do {                                                                   \
        if (!(cond)) {                                                     \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                  \
            fprintf(stderr, "\n");                                         \
            exit(1);                                                       \
        }                                                                  \
    } while (0)

/* Message i: channel "CH<i % 3>", i * 37 % 3001 bytes of a pattern from i. */
static void message(uint64_t i, char *channel, unsigned char *data, uint32_t *len)
{
    snprintf(channel, 16, "CH%u", (unsigned)(i % 3));
    *len = (uint32_t)(i * 37 % 3001);
    for (uint32_t k = 0; k < *len; k++)
        data[k] = (unsigned char)(i * 131 + k);
}

static int same(uint64_t i, const char *channel, const void *data, uint32_t len)
{
    char ch[16];
    static _Thread_local unsigned char want[4096];
    uint32_t n;
    message(i, ch, want, &n);
    return strcmp(ch, channel) == 0 && n == len && memcmp(want, data, n) == 0;
}

static void sleep_us(long us)
{
    struct timespec ts = {us / 1000000, (us % 1000000) * 1000};
    nanosleep(&ts, NULL);
}

typedef struct {
    msg_queue_t *q;
    _Atomic uint64_t seen;    /* messages checked, counted before pop() */
    uint64_t bad;             /* first out-of-order or corrupt index + 1 */
    long delay_every;         /* sleep 50 us every this many messages (0: never) */
} consumer_t;

static void *consume(void *arg)
{
    consumer_t *c = arg;
    const char *ch;
    const void *data;
    uint32_t len;
    while (msg_queue_peek(c->q, &ch, &data, &len) == 0) {
        uint64_t i = atomic_load(&c->seen);
        if (!c->bad && !same(i, ch, data, len))
            c->bad = i + 1;
        if (c->delay_every && i % (uint64_t)c->delay_every == 0)
            sleep_us(50);
        atomic_store(&c->seen, i + 1);
        msg_queue_pop(c->q);
    }
    return NULL;
}

static void queue_case(size_t slots, uint32_t spin_ns, long delay_every, uint64_t n)
{
    consumer_t c = {.q = msg_queue_create(slots, spin_ns), .delay_every = delay_every};
    atomic_init(&c.seen, 0);
    CHECK(c.q, "create");
    pthread_t th;
    CHECK(pthread_create(&th, NULL, consume, &c) == 0, "thread");
    char ch[16];
    unsigned char data[4096];
    uint32_t len;
    for (uint64_t i = 0; i < n; i++) {
        message(i, ch, data, &len);
        CHECK(msg_queue_push(c.q, ch, data, len) == 0, "push %llu", (unsigned long long)i);
        if (i % 97 == 96) { /* after a flush, the consumer has done everything pushed */
            msg_queue_flush(c.q);
            CHECK(atomic_load(&c.seen) == i + 1, "flush returned with %llu of %llu done",
                  (unsigned long long)atomic_load(&c.seen), (unsigned long long)(i + 1));
            CHECK(msg_queue_pending(c.q) == 0, "pending after flush");
        }
    }
    /* close with messages still queued: the consumer drains them first */
    msg_queue_close(c.q);
    CHECK(msg_queue_push(c.q, "X", "", 0) == -1, "push after close accepted");
    pthread_join(th, NULL);
    CHECK(!c.bad, "message %llu out of order or corrupt", (unsigned long long)(c.bad - 1));
    CHECK(atomic_load(&c.seen) == n, "consumer saw %llu of %llu",
          (unsigned long long)atomic_load(&c.seen), (unsigned long long)n);
    msg_queue_stats_t st;
    msg_queue_get_stats(c.q, &st);
    CHECK(st.pushed == n && st.popped == n, "stats %llu %llu", (unsigned long long)st.pushed,
          (unsigned long long)st.popped);
    CHECK(st.flushes == n / 97, "flushes %llu", (unsigned long long)st.flushes);
    printf("ok queue slots=%zu spin=%uns delay_every=%ld: %llu messages in order, "
           "%llu full waits, %llu consumer sleeps\n", slots, spin_ns, delay_every,
           (unsigned long long)n, (unsigned long long)st.full_waits,
           (unsigned long long)st.consumer_sleeps);
    /* a slow consumer and a 4-slot queue: pushes must have waited */
    if (delay_every && slots <= 4)
        CHECK(st.full_waits > 0, "no push waited on a full queue");
    msg_queue_destroy(c.q);
}

static void test_queue(void)
{
    /* Counts sized for a loaded 2-core test machine: spinning threads that share
       a core with the rest of the suite took 36 s at 4x these; order and the
       waits are asserted either way. */
    queue_case(4, 0, 10, 5000);           /* tiny, no spin: every hand-over sleeps */
    queue_case(4, 20000, 10, 5000);       /* tiny, spinning */
    queue_case(1, 5000, 0, 2000);         /* one slot: strict ping-pong */
    queue_case(512, 50000, 0, 50000);     /* the simulator's shape */
    CHECK(msg_queue_create(0, 0) == NULL, "a queue of 0 slots");
}

/* ------------------------------------------------------------ over LCM */
typedef struct {
    uint64_t received;
    uint64_t bad;
} recv_t;

static void on_msg(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    recv_t *r = user;
    if (!r->bad && !same(r->received, channel, rbuf->data, rbuf->data_size))
        r->bad = r->received + 1;
    r->received++;
}

static void test_lcm(const char *url)
{
    lcm_t *rx = lcm_create(url);
    CHECK(rx, "lcm_create(%s)", url);
    recv_t r = {0, 0};
    /* liblcm keeps 30 messages per subscription by default: a burst is more */
    lcm_subscription_set_queue_capacity(lcm_subscribe(rx, "CH.*", on_msg, &r), 10000);
    auv_lcm_sender_t *s = auv_lcm_sender_create(url, 8, 50);
    CHECK(s, "sender");
    char ch[16];
    unsigned char data[4096];
    uint32_t len;
    const uint64_t n = 3000, burst = 50;
    for (uint64_t i = 0; i < n; i += burst) {
        for (uint64_t k = i; k < i + burst; k++) {
            message(k, ch, data, &len);
            CHECK(auv_lcm_sender_publish(s, ch, data, len) == 0, "publish");
        }
        auv_lcm_sender_flush(s);
        CHECK(auv_lcm_sender_pending(s) == 0, "pending after flush");
        /* a burst at a time: the receiver's socket buffer never overflows */
        for (int tries = 0; r.received < i + burst && tries < 1000; tries++)
            lcm_handle_timeout(rx, 10);
        CHECK(r.received == i + burst, "received %llu of %llu", (unsigned long long)r.received,
              (unsigned long long)(i + burst));
    }
    CHECK(!r.bad, "message %llu out of order or corrupt", (unsigned long long)(r.bad - 1));
    auv_lcm_sender_stats_t st;
    auv_lcm_sender_get_stats(s, &st);
    CHECK(st.published == n && st.sent == n && st.send_errors == 0, "stats");
    CHECK(st.full_waits > 0, "bursts of %llu into 8 slots never waited", (unsigned long long)burst);
    CHECK(auv_lcm_sender_last_error(s) == 0, "last error");
    /* destroy sends what is still queued */
    for (uint64_t k = n; k < n + 20; k++) {
        message(k, ch, data, &len);
        auv_lcm_sender_publish(s, ch, data, len);
    }
    auv_lcm_sender_destroy(s);
    for (int tries = 0; r.received < n + 20 && tries < 1000; tries++)
        lcm_handle_timeout(rx, 10);
    CHECK(r.received == n + 20 && !r.bad, "after destroy: %llu", (unsigned long long)r.received);
    printf("ok lcm: %llu messages (up to 3000 B, fragmented above 1400) received in order, "
           "%llu full waits, %llu sender sleeps\n", (unsigned long long)r.received,
           (unsigned long long)st.full_waits, (unsigned long long)st.sender_sleeps);
    lcm_destroy(rx);
    CHECK(auv_lcm_sender_create("nosuchprovider://x", 8, 0) == NULL, "bad URL accepted");
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "queue") == 0)
        test_queue();
    else if (argc == 3 && strcmp(argv[1], "lcm") == 0)
        test_lcm(argv[2]);
    else {
        fprintf(stderr, "usage: %s queue | lcm URL\n", argv[0]);
        return 2;
    }
    return 0;
}
