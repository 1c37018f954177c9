#include "recorder/rec_writer.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static int64_t mono_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static void write_one(rec_writer *w, rec_event *e)
{
    lcm_eventlog_event_t le;
    le.eventnum = 0;            /* lcm_eventlog numbers events itself */
    le.timestamp = e->timestamp;
    le.channellen = e->channellen;
    le.datalen = e->datalen;
    le.channel = e->bytes;
    le.data = e->bytes + e->channellen;
    if (lcm_eventlog_write_event(w->log, &le) == 0) {
        w->written++;
        w->bytes += 28 + e->channellen + e->datalen;   /* the event header is 28 bytes */
    } else if (w->write_errors++ == 0) {
        perror("recorder: writing the log");
    }
}

static void *run(void *arg)
{
    rec_writer *w = arg;
    int64_t last_flush = mono_ms();
    for (;;) {
        int closed = 0;
        rec_event *list = rec_queue_take_all(w->q, w->flush_ms, &closed);
        while (list) {
            rec_event *next = list->next;
            write_one(w, list);
            free(list);
            list = next;
        }
        int64_t now = mono_ms();
        if (closed || now - last_flush >= w->flush_ms) {
            if (fflush(w->log->f) != 0 && w->write_errors++ == 0)
                perror("recorder: flushing the log");
            last_flush = now;
        }
        if (closed && rec_queue_bytes(w->q) == 0)
            return NULL;
    }
}

int rec_writer_start(rec_writer *w, rec_queue *q, lcm_eventlog_t *log, int flush_ms)
{
    w->q = q;
    w->log = log;
    w->flush_ms = flush_ms > 0 ? flush_ms : 100;
    w->written = w->bytes = w->write_errors = 0;
    return pthread_create(&w->thread, NULL, run, w) ? -1 : 0;
}

void rec_writer_finish(rec_writer *w)
{
    rec_queue_close(w->q);
    pthread_join(w->thread, NULL);
}
