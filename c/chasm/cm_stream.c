/* Message variables (cm_stream.h): rings of blobs, readers' places, posts. */
#include <stdlib.h>
#include <string.h>

#include "chasm/cm_machine.h"
#include "chasm/cm_stream.h"

cm_stream *cm_stream_new(chasm_machine *m, cm_var *v, uint32_t capacity)
{
    cm_stream *s = calloc(1, sizeof *s);
    if (!s) return NULL;
    s->ring = calloc(capacity, sizeof *s->ring);
    s->pending = calloc(capacity, sizeof *s->pending);
    if (!s->ring || !s->pending) {
        free(s->ring);
        free(s->pending);
        free(s);
        return NULL;
    }
    s->var = v;
    s->capacity = capacity;
    s->next = m->streams;
    m->streams = s;
    return s;
}

void cm_streams_free(chasm_machine *m)
{
    while (m->streams) {
        cm_stream *s = m->streams;
        m->streams = s->next;
        for (uint32_t i = 0; i < s->capacity; i++) {
            free(s->ring[i].data);
            free(s->pending[i].data);
        }
        free(s->ring);
        free(s->pending);
        free(s);
    }
}

void cm_streams_begin_cycle(chasm_machine *m)
{
    for (cm_stream *s = m->streams; s; s = s->next) {
        s->cycle_first = s->seen_head;
        s->seen_head = s->head;
    }
}

void cm_streams_commit(chasm_machine *m, int64_t now)
{
    for (cm_stream *s = m->streams; s; s = s->next) {
        if (!s->n_pending) continue;
        for (uint32_t i = 0; i < s->n_pending; i++) {
            /* swap, not copy: the evicted message's buffer is reused by the next post */
            cm_blob *slot = &s->ring[s->head % s->capacity];
            cm_blob t = *slot;
            *slot = s->pending[i];
            s->pending[i] = t;
            s->pending[i].len = 0;
            s->head++;
        }
        s->n_pending = 0;
        s->var->updated_us = now;
        s->var->has_value = true;
    }
}

const void *cm_stream_next(cm_stream *s, uint64_t *next, size_t *len)
{
    uint64_t oldest = s->head > s->capacity ? s->head - s->capacity : 0;
    if (*next < oldest) {
        s->missed += oldest - *next;
        *next = oldest;
    }
    if (*next >= s->head) {
        if (len) *len = 0;
        return NULL;
    }
    const cm_blob *b = &s->ring[*next % s->capacity];
    (*next)++;
    if (len) *len = b->len;
    /* a zero-length message is a message too: hand out a valid pointer */
    return b->data ? (const void *)b->data : (const void *)"";
}

/* Makes b hold len bytes; the buffer only grows. */
static int blob_fit(cm_blob *b, size_t len)
{
    if (len <= b->cap && b->data) return 0;
    size_t cap = len < 64 ? 64 : len;
    unsigned char *d = realloc(b->data, cap);
    if (!d) return -1;
    b->data = d;
    b->cap = cap;
    return 0;
}

int cm_stream_post(cm_stream *s, const void *data, size_t len)
{
    if ((!data && len) || len > CHASM_MESSAGE_MAX_BYTES || s->n_pending >= s->capacity) {
        s->refused++;
        return -1;
    }
    cm_blob *b = &s->pending[s->n_pending];
    if (blob_fit(b, len)) {
        s->refused++;
        return -1;
    }
    if (len) memcpy(b->data, data, len);
    b->len = len;
    s->n_pending++;
    return 0;
}

/* ------------------------------------------------------------ host side */

static cm_stream *stream_of(const chasm_machine *m, int id)
{
    return id >= 0 && id < m->n_vars && m->vars[id].type == CHASM_MESSAGES ? m->vars[id].stream : NULL;
}

int chasm_messages_append(chasm_machine *m, int id, const void *data, size_t len, int64_t utime)
{
    cm_stream *s = stream_of(m, id);
    if (!s || (!data && len) || len > CHASM_MESSAGE_MAX_BYTES) return -1;
    cm_blob *b = &s->ring[s->head % s->capacity];
    if (blob_fit(b, len)) return -1;
    if (len) memcpy(b->data, data, len);
    b->len = len;
    s->head++;
    s->var->updated_us = utime;
    s->var->has_value = true;
    return 0;
}

const void *chasm_messages_take(chasm_machine *m, int id, size_t *len)
{
    cm_stream *s = stream_of(m, id);
    if (!s) {
        if (len) *len = 0;
        return NULL;
    }
    return cm_stream_next(s, &s->host_next, len);
}

int chasm_messages_stats(const chasm_machine *m, int id, chasm_messages_info *out)
{
    const cm_stream *s = stream_of(m, id);
    if (!s || !out) return -1;
    out->capacity = s->capacity;
    out->total = s->head;
    out->missed = s->missed;
    out->refused = s->refused;
    return 0;
}
