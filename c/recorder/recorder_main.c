/* auv-recorder: the project's LCM recorder, which loses nothing it receives.
 *
 *   auv-recorder -f run.lcmlog [--lcm-url URL] [--stats stats.json] ...
 *
 * Why not lcm-logger: its subscription queue holds 30 messages and cannot be
 * sized, so a logger descheduled for a moment on a busy machine drops
 * messages (0.6-1.5 % of each vehicle's TRUTH in a 3-vehicle fast-time demo).
 * Here the subscription queue is deep, the socket receive buffer large, and
 * the handler only copies each message into a queue that a writer thread
 * takes to disk, so a slow disk never stalls reception. In a lockstep world
 * the recorder is a participant (SIM.<NAME>, the managers' lockstep code):
 * it reports a step done once it has taken in everything received before
 * that step's clock, and holds time while its queue is over half full.
 * The record ends at the mission's end: once the launcher's annotation
 * `mission end` (SIM.ANNOTATION, KIND_EVENT) came, only annotations are
 * written (the launcher's notes of the stop, its summary); what the world
 * still sends while it is stopped (repeated lockstep reports, leaves, health)
 * is counted as after_end, not recorded (docs/scenarios.md, "End").
 * Counts: received, written, dropped (its own queue full), missed (datagrams
 * the kernel dropped at its socket), after_end, printed at exit, in --stats and each
 * health period on SIM.HEALTH. Output: an ordinary LCM event log.
 * Exit: 0 ok, 1 could not record (or a write failed), 2 usage. */
#include <errno.h>
#include <lcm/eventlog.h>
#include <lcm/lcm.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "auv/auv_log_annotation_t.h"
#include "auv/auv_sim_clock_t.h"
#include "managers/mgr_lockstep.h"
#include "recorder/rec_health.h"
#include "recorder/rec_input.h"
#include "recorder/rec_options.h"
#include "recorder/rec_queue.h"
#include "recorder/rec_socket.h"
#include "recorder/rec_writer.h"

static volatile sig_atomic_t g_stop;

static void on_signal(int sig)
{
    (void)sig;
    g_stop = 1;
}

typedef struct {
    rec_options opt;
    lcm_t *lcm;                 /* publishing (and receiving on a url that is not udpm) */
    rec_input in;
    rec_queue q;
    rec_writer w;
    rec_socket sock;
    mgr_lockstep ls;
    int64_t received;           /* taken in for the record (not after the end) */
    int64_t after_end;          /* received after the mission's end mark, not recorded */
    int ended;                  /* the launcher's `mission end` came */
    int64_t last_clock_utime;
    int64_t drops0;             /* kernel drops on the socket before we began */
} recorder;

static double mono_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

#define ANNOTATION_CHANNEL "SIM.ANNOTATION"
#define END_MARK "mission end"

/* The launcher's mark of the mission's end (tools/launch/launcher.py). */
static int is_end_mark(const void *data, int len)
{
    auv_log_annotation_t a;
    if (auv_log_annotation_t_decode(data, 0, len, &a) < 0)
        return 0;
    int end = a.kind == AUV_LOG_ANNOTATION_T_KIND_EVENT && a.name && !strcmp(a.name, END_MARK);
    auv_log_annotation_t_decode_cleanup(&a);
    return end;
}

static void on_message(const char *channel, const void *data, int len, int64_t recv_utime, void *user)
{
    recorder *r = user;
    int annotation = !strcmp(channel, ANNOTATION_CHANNEL);
    if (r->ended && !annotation) {
        r->after_end++;
    } else {
        r->received++;
        rec_queue_push(&r->q, recv_utime, channel, data, (int32_t)len);
        if (annotation && !r->ended && is_end_mark(data, len))
            r->ended = 1;
    }
    if (!strcmp(channel, "SIM.CLOCK")) { /* still a participant after the end, while the world stops */
        auv_sim_clock_t c;
        if (auv_sim_clock_t_decode(data, 0, len, &c) >= 0) {
            r->last_clock_utime = c.utime;
            if (r->opt.lockstep)
                mgr_lockstep_on_clock(&r->ls, r->lcm, &c);
            auv_sim_clock_t_decode_cleanup(&c);
        }
    }
}

static int64_t missed(const recorder *r)
{
    int64_t d = rec_socket_drops(&r->sock);
    return d < 0 ? -1 : d - r->drops0;
}

static void write_stats(const recorder *r, int64_t dropped, int64_t miss)
{
    if (!r->opt.stats)
        return;
    FILE *f = fopen(r->opt.stats, "w");
    if (!f) {
        perror(r->opt.stats);
        return;
    }
    const lcm_udpm_counts *wire = r->in.all ? lcm_udpm_reader_counts(r->in.all) : NULL;
    fprintf(f, "{\"received\": %lld, \"written\": %lld, \"dropped\": %lld, \"missed\": %lld, "
               "\"after_end\": %lld, \"malformed\": %lld, \"incomplete\": %lld, "
               "\"write_errors\": %lld, \"bytes\": %lld, \"queue_high_water_bytes\": %zu, "
               "\"recv_buf_requested\": %ld, \"recv_buf_granted\": %d, \"rmem_max\": %ld}\n",
            (long long)r->received, (long long)r->w.written, (long long)dropped, (long long)miss,
            (long long)r->after_end, (long long)(wire ? wire->malformed : 0), (long long)(wire ? wire->incomplete : 0),
            (long long)r->w.write_errors, (long long)r->w.bytes, r->q.high_water, r->opt.recv_buf,
            r->sock.granted_bytes, rec_rmem_max());
    fclose(f);
}

/* Take in what is already on its way, then stop: nothing received is lost. */
static void drain(recorder *r)
{
    double until = mono_s() + 2.0;
    double quiet_until = mono_s() + 0.05;
    while (mono_s() < until && mono_s() < quiet_until) {
        if (rec_input_wait(&r->in, REC_INPUT_TICK_MS) > 0)
            quiet_until = mono_s() + 0.05;
    }
}

static void run(recorder *r)
{
    rec_health h;
    rec_health_init(&h);
    double next_health = mono_s() + r->opt.health_period_s;
    int failures = 0;
    while (!g_stop) {
        if (rec_input_wait(&r->in, 50) < 0) {
            /* a signal interrupts the wait (EINTR): the loop condition decides */
            if (g_stop || errno == EINTR)
                continue;
            if (++failures == 100) {
                fprintf(stderr, "auv-recorder: receiving keeps failing: %s\n", strerror(errno));
                break;
            }
            continue;
        }
        failures = 0;
        if (r->opt.lockstep) {
            /* time waits while the writer is far behind */
            while (!g_stop && r->ls.lockstep && !rec_queue_wait_below(&r->q, r->q.capacity / 2, 100))
                ;
            mgr_lockstep_poll(&r->ls, r->lcm);
        }
        if (r->opt.health_period_s > 0 && mono_s() >= next_health) {
            next_health = mono_s() + r->opt.health_period_s;
            int64_t m = missed(r);
            rec_health_publish(&h, r->lcm, "recorder", r->last_clock_utime, r->received,
                               rec_queue_dropped(&r->q) + (m > 0 ? m : 0));
        }
    }
}

int main(int argc, char **argv)
{
    static recorder r;
    int rc = rec_parse_args(&r.opt, argc, argv);
    if (rc)
        return rc == 1 ? 0 : 2;
    setvbuf(stdout, NULL, _IOLBF, 0);
    char *url = rec_url_with_recv_buf(r.opt.url, r.opt.recv_buf);
    r.lcm = url ? lcm_create(url) : NULL;
    if (!r.lcm || rec_queue_init(&r.q, r.opt.queue_bytes)) {
        fprintf(stderr, "auv-recorder: cannot start LCM on %s\n", url ? url : r.opt.url);
        free(url);
        return 1;
    }
    mgr_lockstep_init(&r.ls, "SIM", r.opt.name);
    if (rec_input_open(&r.in, url, r.opt.recv_buf, r.opt.channel, r.lcm, r.opt.lcm_queue, on_message, &r))
        return 1;
    if (rec_socket_of(&r.sock, rec_input_socket(&r.in)) == 0) {
        r.drops0 = rec_socket_drops(&r.sock);
        if (r.drops0 < 0)
            r.drops0 = 0;
    }
    /* The file only once the socket is open: whoever sees it (the launcher
     * writes its note `logger` then) is heard. Created before, a message sent
     * between the two was lost on a loaded machine, and two runs' logs
     * differed by that one event (docs/scenarios.md, "End"). */
    lcm_eventlog_t *log = lcm_eventlog_create(r.opt.file, "w");
    if (!log) {
        perror(r.opt.file);
        rec_input_close(&r.in);
        lcm_destroy(r.lcm);
        rec_queue_destroy(&r.q);
        free(url);
        return 1;
    }
    if (rec_writer_start(&r.w, &r.q, log, r.opt.flush_ms)) {
        fprintf(stderr, "auv-recorder: cannot start the writer thread\n");
        return 1;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    if (!r.opt.quiet) {
        printf("auv-recorder: recording %s to %s\n", url, r.opt.file);
        if (r.sock.fd >= 0)
            printf("auv-recorder: socket receive buffer: asked %ld bytes, kernel granted %d "
                   "(it doubles the request, capped at 2 x net.core.rmem_max = 2 x %ld)\n",
                   r.opt.recv_buf, r.sock.granted_bytes, rec_rmem_max());
        else
            printf("auv-recorder: receive socket not found: kernel drops cannot be counted\n");
    }

    run(&r);
    drain(&r);
    if (r.opt.lockstep)
        mgr_lockstep_leave(&r.ls, r.lcm);
    rec_writer_finish(&r.w);
    int64_t dropped = rec_queue_dropped(&r.q), miss = missed(&r);
    write_stats(&r, dropped, miss);
    printf("auv-recorder: received %lld, written %lld, dropped %lld (own queue full), missed %s%lld "
           "(kernel socket drops), %lld after the mission's end not recorded%s\n",
           (long long)r.received, (long long)r.w.written, (long long)dropped, miss < 0 ? "unknown " : "",
           (long long)(miss < 0 ? 0 : miss), (long long)r.after_end, r.w.write_errors ? ", WRITE ERRORS" : "");
    const lcm_udpm_counts *wire = r.in.all ? lcm_udpm_reader_counts(r.in.all) : NULL;
    if (wire && (wire->malformed || wire->incomplete))
        printf("auv-recorder: not recorded: %lld malformed datagrams, %lld fragmented messages never completed\n",
               (long long)wire->malformed, (long long)wire->incomplete);
    rec_input_close(&r.in);
    lcm_destroy(r.lcm);
    lcm_eventlog_destroy(log);
    rec_queue_destroy(&r.q);
    free(url);
    return r.w.write_errors ? 1 : 0;
}
