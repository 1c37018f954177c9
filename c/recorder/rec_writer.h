/* The recorder's writer thread: takes events from the queue and appends
 * them to an ordinary LCM event log (lcm_eventlog), flushing at least every
 * flush_ms so a crash loses little; the file is complete once it is joined.
 * Disk stalls here never stall reception. */
#ifndef REC_WRITER_H
#define REC_WRITER_H

#include <lcm/eventlog.h>
#include <pthread.h>
#include <stdint.h>

#include "recorder/rec_queue.h"

typedef struct {
    rec_queue *q;
    lcm_eventlog_t *log;
    int flush_ms;
    pthread_t thread;
    /* written by the thread, read after join (or approximately, for health) */
    volatile int64_t written;
    volatile int64_t bytes;
    volatile int64_t write_errors;
} rec_writer;

int rec_writer_start(rec_writer *w, rec_queue *q, lcm_eventlog_t *log, int flush_ms);
/* Closes the queue, waits until everything queued is written and flushed. */
void rec_writer_finish(rec_writer *w);

#endif
