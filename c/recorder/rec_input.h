/* Where the recorder's messages come from.
 *
 * On a udpm url it reads the group on sockets of its own
 * (common/lcm_udpm_reader.h): one takes every datagram and is read in
 * batches, never woken for; a second lets only SIM.CLOCK through (a kernel
 * channel filter) and is what the recorder sleeps on. A clock means a step:
 * the recorder then reads everything queued, which holds every message sent
 * before that clock, and may report the step done. Without a clock it reads
 * every REC_INPUT_TICK_MS; after a read that took over an eighth of the
 * socket's buffer (a burst) it wakes for the data itself until it is quiet. Through liblcm, each datagram cost two wake-ups
 * (its receive thread, then the handler): a third of all the context
 * switches of an 8-vehicle run.
 *
 * Any other url goes through liblcm, as before, and so does every url with
 * AUV_LCM_READER=0 in the environment. */
#ifndef REC_INPUT_H
#define REC_INPUT_H

#include <lcm/lcm.h>
#include <stdint.h>

#include "common/lcm_udpm_reader.h"

#define REC_INPUT_TICK_MS 10

/* One message: channel, payload, receive time [us since the epoch]. */
typedef void (*rec_input_fn)(const char *channel, const void *data, int len, int64_t recv_utime, void *user);

typedef struct {
    lcm_udpm_reader_t *all, *clock;  /* NULL: through liblcm */
    lcm_t *lcm;                      /* publishing; receiving when all is NULL */
    lcm_subscription_t *sub;
    int liblcm_fd;                   /* liblcm's receive socket, -1 unknown */
    void *regex;                     /* the --channel pattern; NULL: every channel */
    rec_input_fn fn;
    void *user;
    int64_t clock_woken_utime, clock_all_utime;  /* newest SIM.CLOCK read on each socket */
    int64_t last_bytes;              /* payload bytes the last wait read */
} rec_input;

/* Opens the input for url (recv_buf: the receive buffer to ask for) and the
 * channel regex (anchored, as lcm_subscribe takes it). lcm: the instance the
 * recorder publishes on; lcm_queue: its subscription queue when liblcm
 * receives. 0, or -1 with the reason printed. */
int rec_input_open(rec_input *in, const char *url, long recv_buf, const char *channel, lcm_t *lcm, int lcm_queue,
                   rec_input_fn fn, void *user);
void rec_input_close(rec_input *in);

/* Waits up to timeout_ms for a clock (or, through liblcm, any message), then
 * hands over everything received. Returns the number of messages, -1 on a
 * receive error (errno set; EINTR when a signal came). */
int rec_input_wait(rec_input *in, int timeout_ms);

/* The socket that takes every datagram (its kernel drops are the recorder's
 * misses): its own, or liblcm's found among the process's descriptors; -1
 * when there is none. */
int rec_input_socket(const rec_input *in);

#endif
