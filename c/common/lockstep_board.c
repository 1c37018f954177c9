#define _POSIX_C_SOURCE 200809L /* strdup, clock_gettime */
/* The lockstep clock's board of reports (lockstep_board.h). */
#include "lockstep_board.h"

#include <errno.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* lockstep_t on the wire: fingerprint (8), utime (8), participant (int32
 * length with its NUL, then the bytes and the NUL), kind (1), step (8). */
enum { HEAD_LEN = 20, TAIL_LEN = 9, KIND_STEP_DONE = 1 };

typedef struct {
    char *name;
    int name_len; /* without the NUL */
    int64_t last_done;
} entry;

struct lockstep_board {
    char *channel;
    uint8_t fingerprint[8];
    entry *parts;
    int n, cap;
    int64_t limit;
    int64_t watch; /* the step the clock waits for */
    int64_t taken;
};

static uint32_t be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static uint64_t be64(const uint8_t *p)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++)
        v = v << 8 | p[i];
    return v;
}

lockstep_board_t *lockstep_board_new(const char *channel, uint64_t fingerprint)
{
    lockstep_board_t *b = calloc(1, sizeof *b);
    if (!b || !(b->channel = strdup(channel))) {
        free(b);
        return NULL;
    }
    for (int i = 0; i < 8; i++)
        b->fingerprint[i] = (uint8_t)(fingerprint >> (56 - 8 * i));
    b->limit = -1; /* nothing published yet: take nothing */
    return b;
}

void lockstep_board_free(lockstep_board_t *b)
{
    if (!b)
        return;
    for (int i = 0; i < b->n; i++)
        free(b->parts[i].name);
    free(b->parts);
    free(b->channel);
    free(b);
}

static entry *find(const lockstep_board_t *b, const char *name, int len)
{
    for (int i = 0; i < b->n; i++)
        if (b->parts[i].name_len == len && memcmp(b->parts[i].name, name, (size_t)len) == 0)
            return &b->parts[i];
    return NULL;
}

int lockstep_board_put(lockstep_board_t *b, const char *name, int64_t last_done)
{
    int len = (int)strlen(name);
    entry *e = find(b, name, len);
    if (!e) {
        if (b->n == b->cap) {
            int cap = b->cap ? 2 * b->cap : 16;
            entry *grown = realloc(b->parts, (size_t)cap * sizeof *grown);
            if (!grown)
                return -1;
            b->parts = grown;
            b->cap = cap;
        }
        char *copy = strdup(name);
        if (!copy)
            return -1;
        e = &b->parts[b->n++];
        e->name = copy;
        e->name_len = len;
    }
    e->last_done = last_done;
    return 0;
}

void lockstep_board_remove(lockstep_board_t *b, const char *name)
{
    entry *e = find(b, name, (int)strlen(name));
    if (!e)
        return;
    free(e->name);
    /* keep the order the participants were put in (owing_at lists them so) */
    memmove(e, e + 1, (size_t)(b->parts + b->n - (e + 1)) * sizeof *e);
    b->n--;
}

int64_t lockstep_board_last_done(const lockstep_board_t *b, const char *name)
{
    const entry *e = find(b, name, (int)strlen(name));
    return e ? e->last_done : LOCKSTEP_BOARD_UNKNOWN;
}

void lockstep_board_set_limit(lockstep_board_t *b, int64_t limit)
{
    b->limit = limit;
}

void lockstep_board_set_watch(lockstep_board_t *b, int64_t step)
{
    b->watch = step;
}

static void copy_name(const entry *e, char *out, int out_len)
{
    if (out_len <= 0)
        return;
    int n = e->name_len < out_len - 1 ? e->name_len : out_len - 1;
    memcpy(out, e->name, (size_t)n);
    out[n] = '\0';
}

int lockstep_board_owing(const lockstep_board_t *b, int64_t step)
{
    int owing = 0;
    for (int i = 0; i < b->n; i++)
        owing += b->parts[i].last_done < step;
    return owing;
}

int lockstep_board_owing_at(const lockstep_board_t *b, int64_t step, int k, char *out, int out_len)
{
    for (int i = 0; i < b->n; i++)
        if (b->parts[i].last_done < step && k-- == 0) {
            copy_name(&b->parts[i], out, out_len);
            return 1;
        }
    return 0;
}

int64_t lockstep_board_taken(const lockstep_board_t *b)
{
    return b->taken;
}

int lockstep_board_take(lockstep_board_t *b, const char *channel, const void *data, int len)
{
    const uint8_t *p = data;
    if (len < HEAD_LEN + 1 + TAIL_LEN || strcmp(channel, b->channel) != 0 || memcmp(p, b->fingerprint, 8) != 0)
        return 0;
    uint64_t n = be32(p + 16); /* the participant's length, with its NUL */
    if (n < 1 || (uint64_t)len != HEAD_LEN + n + TAIL_LEN || p[HEAD_LEN + n - 1] != 0)
        return 0; /* not exactly one lockstep_t: Python says what is wrong with it */
    const uint8_t *tail = p + HEAD_LEN + n;
    if (tail[0] != KIND_STEP_DONE)
        return 0;
    int64_t step = (int64_t)be64(tail + 1);
    entry *e = find(b, (const char *)p + HEAD_LEN, (int)n - 1);
    if (!e || step <= e->last_done || step > b->limit)
        return 0; /* unknown, a repeat (Python acts on it), or a step never published */
    e->last_done = step;
    b->taken++;
    return 1;
}

int lockstep_board_next(lockstep_board_t *b, lcm_udpm_reader_t *r, lcm_udpm_msg *m)
{
    int took = 0;
    for (;;) {
        int rc = lcm_udpm_reader_next(r, m);
        if (rc != 1)
            return rc == 0 && took && lockstep_board_owing(b, b->watch) == 0 ? 2 : rc;
        if (!lockstep_board_take(b, m->channel, m->data, m->len))
            return 1;
        took = 1;
    }
}

static int64_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

int lockstep_board_wait(lockstep_board_t *b, lcm_udpm_reader_t *r, lcm_udpm_msg *m, int timeout_ms)
{
    int64_t until = now_ms() + (timeout_ms > 0 ? timeout_ms : 0);
    for (;;) {
        int rc = lockstep_board_next(b, r, m);
        if (rc != 0)
            return rc;
        int64_t left = until - now_ms();
        if (left <= 0)
            return 0;
        struct pollfd p = {.fd = lcm_udpm_reader_fd(r), .events = POLLIN};
        int n = poll(&p, 1, (int)left);
        if (n < 0 && errno != EINTR)
            return -1;
        if (n <= 0)
            return 0; /* the time is up, or a signal: the caller's handlers run */
    }
}
