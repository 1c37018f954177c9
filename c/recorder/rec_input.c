#include "recorder/rec_input.h"

#include <errno.h>
#include <poll.h>
#include <regex.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/lcm_chanfilter.h"
#include "common/lcm_socket.h"

static int wanted(const rec_input *in, const char *channel)
{
    return !in->regex || regexec(in->regex, channel, 0, NULL, 0) == 0;
}

/* The time a SIM.CLOCK message carries (sim_clock_t: the fingerprint, then
 * utime, big-endian), INT64_MIN for anything else. */
static int64_t clock_utime(const char *channel, const void *data, int len)
{
    if (strcmp(channel, "SIM.CLOCK") != 0 || len < 16)
        return INT64_MIN;
    const unsigned char *p = (const unsigned char *)data + 8;
    uint64_t u = 0;
    for (int i = 0; i < 8; i++)
        u = u << 8 | p[i];
    return (int64_t)u;
}

static void on_udpm(const char *channel, const void *data, int len, int64_t recv_utime, void *user)
{
    rec_input *in = user;
    int64_t t = clock_utime(channel, data, len);
    if (t > in->clock_all_utime)
        in->clock_all_utime = t;
    in->last_bytes += len;
    if (wanted(in, channel))
        in->fn(channel, data, len, recv_utime, in->user);
}

static void on_lcm(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    rec_input *in = user;
    in->fn(channel, rbuf->data, (int)rbuf->data_size, rbuf->recv_utime, in->user);
}

/* Nothing of the clock socket is recorded (the other socket has every
 * datagram): it only wakes the recorder, and counts. */
static void count_clock(const char *channel, const void *data, int len, int64_t recv_utime, void *user)
{
    (void)recv_utime;
    rec_input *in = user;
    int64_t t = clock_utime(channel, data, len);
    if (t > in->clock_woken_utime)
        in->clock_woken_utime = t;
}

/* liblcm's receive socket: the first on the port (the recorder has one instance). */
static int take_first(int fd, ino_t inode, void *user)
{
    (void)inode;
    *(int *)user = fd;
    return 1;
}

static int compile_channel(rec_input *in, const char *channel)
{
    if (!strcmp(channel, ".*"))
        return 0;
    in->regex = malloc(sizeof(regex_t));
    if (!in->regex)
        return -1;
    if (lcm_udpm_pattern_compile(in->regex, channel) != 0) {
        fprintf(stderr, "auv-recorder: --channel '%s' is not a regular expression\n", channel);
        free(in->regex);
        in->regex = NULL;
        return -1;
    }
    return 0;
}

int rec_input_open(rec_input *in, const char *url, long recv_buf, const char *channel, lcm_t *lcm, int lcm_queue,
                   rec_input_fn fn, void *user)
{
    memset(in, 0, sizeof *in);
    in->clock_woken_utime = in->clock_all_utime = INT64_MIN;
    in->lcm = lcm;
    in->fn = fn;
    in->user = user;
    char err[160];
    int own = lcm_udpm_reader_enabled(); /* off: liblcm receives, as in every process then */
    in->all = own ? lcm_udpm_reader_open(url, recv_buf, err, sizeof err) : NULL;
    if (!in->all) {
        if (own && url && !strncmp(url, "udpm://", 7)) {
            fprintf(stderr, "auv-recorder: cannot receive on %s: %s\n", url, err);
            return -1;
        }
        in->sub = lcm_subscribe(lcm, channel, on_lcm, in);
        if (!in->sub) {
            fprintf(stderr, "auv-recorder: cannot subscribe to '%s'\n", channel);
            return -1;
        }
        lcm_subscription_set_queue_capacity(in->sub, lcm_queue);
        in->liblcm_fd = -1; /* found for its kernel drops; liblcm keeps it to itself */
        lcm_sockets_on_port(lcm_url_port(url), take_first, &in->liblcm_fd);
        return 0;
    }
    if (compile_channel(in, channel))
        return -1;
    in->clock = lcm_udpm_reader_open(url, 0, err, sizeof err);
    if (!in->clock) {
        fprintf(stderr, "auv-recorder: cannot receive on %s: %s\n", url, err);
        return -1;
    }
    auv_chanfilter_rule_t clock_only = {.channel = "SIM\\.CLOCK"};
    if (auv_chanfilter_enabled() && auv_chanfilter_attach_fd(lcm_udpm_reader_fd(in->clock), &clock_only, 1) != 1) {
        /* without the filter it would wake for every datagram, as liblcm did */
        lcm_udpm_reader_close(in->clock);
        in->clock = NULL;
    }
    return 0;
}

void rec_input_close(rec_input *in)
{
    if (in->sub)
        lcm_unsubscribe(in->lcm, in->sub);
    lcm_udpm_reader_close(in->all);
    lcm_udpm_reader_close(in->clock);
    if (in->regex) {
        regfree(in->regex);
        free(in->regex);
    }
    memset(in, 0, sizeof *in);
}

int rec_input_wait(rec_input *in, int timeout_ms)
{
    if (!in->all)
        return lcm_handle_timeout(in->lcm, timeout_ms);
    /* Busy (the last read took over an eighth of the socket's buffer: a
     * burst, or a world not paced by a clock): wake for the data itself, so
     * the buffer never fills between two ticks. Otherwise sleep on the clock. */
    int busy = in->last_bytes > lcm_udpm_reader_granted(in->all) / 8;
    struct pollfd p[2] = {{.fd = in->clock ? lcm_udpm_reader_fd(in->clock) : -1, .events = POLLIN},
                          {.fd = busy ? lcm_udpm_reader_fd(in->all) : -1, .events = POLLIN}};
    int rc = poll(p, 2, timeout_ms < REC_INPUT_TICK_MS ? timeout_ms : REC_INPUT_TICK_MS);
    if (rc < 0)
        return -1;
    if ((p[0].revents & POLLIN) && lcm_udpm_reader_drain(in->clock, count_clock, in) < 0)
        return -1;
    /* After the clock, every message sent before it has been queued on the
     * other socket too. The kernel hands one datagram to the group's sockets
     * one after the other, so the clock itself may still be on its way there:
     * wait for it briefly (a datagram the kernel dropped must not hold us). */
    in->last_bytes = 0;
    int n = lcm_udpm_reader_drain(in->all, on_udpm, in);
    for (int tries = 0; n >= 0 && in->clock_all_utime < in->clock_woken_utime && tries < 5; tries++) {
        struct pollfd q = {.fd = lcm_udpm_reader_fd(in->all), .events = POLLIN};
        if (poll(&q, 1, 1) < 0)
            return -1;
        int more = lcm_udpm_reader_drain(in->all, on_udpm, in);
        n = more < 0 ? -1 : n + more;
    }
    return n;
}

int rec_input_socket(const rec_input *in)
{
    return in->all ? lcm_udpm_reader_fd(in->all) : in->liblcm_fd;
}
