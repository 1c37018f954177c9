/* The driver process: flags, LCM, the port, and one poll loop over the port,
 * LCM (SIM.CLOCK with --clock sim, and the protocol's own subscriptions:
 * drv_subs.h) and a 1 Hz timer for the status and
 * health messages. Every read is stamped on the chosen clock, recorded raw
 * when asked (--raw), and handed to the protocol. Nothing in the loop blocks:
 * the port is non-blocking, TCP connects included. */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_raw_bytes_t.h"
#include "common/lcm_rx.h"
#include "drivers/common/drv_clock.h"
#include "drivers/common/drv_options.h"
#include "drivers/common/drv_port.h"
#include "drivers/common/drv_protocol.h"
#include "drivers/common/drv_status.h"
#include "drivers/common/drv_subs.h"

#define TICK_MS 100
#define STATUS_MS 1000
#define READ_CAP 4096

typedef struct {
    const drv_protocol *p;
    void *state;
    drv_options opt;
    lcm_t *lcm;
    drv_clock clock;
    drv_port port;
    drv_ctx ctx;
    drv_status status;
    drv_subs subs;
    char log_prefix[128];
    char raw_channel[128];
    int64_t raw_offset[2]; /* bytes of each direction so far (raw_bytes_t.offset) */
} driver;

static volatile sig_atomic_t stop_requested;
static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

static void lcm_sink(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    (void)type;
    lcm_publish(user, channel, data, (unsigned)len);
}

static void publish_raw(driver *d, int8_t direction, const uint8_t *data, size_t n, int64_t stamp)
{
    int64_t offset = d->raw_offset[direction];
    d->raw_offset[direction] += (int64_t)n;
    if (!d->opt.raw)
        return;
    auv_raw_bytes_t m;
    m.utime = stamp;
    m.vehicle = (char *)d->opt.vehicle;
    m.device = (char *)d->p->device;
    m.direction = direction;
    m.offset = offset;
    m.n_bytes = (int32_t)n;
    m.data = (uint8_t *)data;
    auv_raw_bytes_t_publish(d->lcm, d->raw_channel, &m);
}

/* drv_write for the protocol: to the port, and recorded as DIR_TX. */
static int port_write(void *user, const uint8_t *data, size_t n)
{
    driver *d = user;
    int r = drv_port_write(&d->port, data, n, drv_monotonic_ms());
    int64_t now = drv_clock_now(&d->clock);
    if (r == 0)
        publish_raw(d, AUV_RAW_BYTES_T_DIR_TX, data, n, now < 0 ? 0 : now);
    return r;
}

static void on_bytes(driver *d, const uint8_t *buf, size_t n)
{
    int64_t stamp = drv_clock_now(&d->clock);
    if (stamp < 0) {
        drv_drop(&d->ctx, "no clock yet", "%zu bytes before the first SIM.CLOCK", n);
        return;
    }
    publish_raw(d, AUV_RAW_BYTES_T_DIR_RX, buf, n, stamp);
    if (d->p->tick)
        d->p->tick(d->state, &d->ctx, stamp);
    d->p->feed(d->state, &d->ctx, buf, n, stamp);
}

static int next_timeout(const driver *d, int64_t now_ms, int64_t next_status_ms)
{
    int64_t t = next_status_ms - now_ms;
    if (d->p->tick && t > TICK_MS)
        t = TICK_MS;
    if (d->port.state != DRV_PORT_OPEN && d->port.retry_at_ms - now_ms < t)
        t = d->port.retry_at_ms - now_ms;
    return t < 0 ? 0 : (int)t;
}

static int run(driver *d)
{
    int64_t next_status_ms = drv_monotonic_ms() + STATUS_MS;
    int lcm_fd = d->opt.clock == DRV_CLOCK_SIM || d->subs.n ? lcm_get_fileno(d->lcm) : -1;
    uint8_t buf[READ_CAP];
    int was_open = 0;
    while (!stop_requested && !drv_port_ended(&d->port)) { /* a recording ends the run at its end */
        int64_t now_ms = drv_monotonic_ms();
        drv_port_service(&d->port, now_ms);
        struct pollfd fds[2];
        int nfds = 0, port_i = -1, lcm_i = -1;
        if (drv_port_fd(&d->port) >= 0) {
            port_i = nfds;
            fds[nfds++] = (struct pollfd){.fd = drv_port_fd(&d->port), .events = drv_port_events(&d->port)};
        }
        if (lcm_fd >= 0) {
            lcm_i = nfds;
            fds[nfds++] = (struct pollfd){.fd = lcm_fd, .events = POLLIN};
        }
        int r = poll(fds, (nfds_t)nfds, next_timeout(d, now_ms, next_status_ms));
        if (r < 0 && errno != EINTR) {
            perror("poll");
            return 1;
        }
        now_ms = drv_monotonic_ms();
        if (r > 0 && lcm_i >= 0 && fds[lcm_i].revents) {
            rx_handle_timeout(d->lcm, 0);
            drv_subs_account(&d->subs);
        }
        if (r > 0 && port_i >= 0 && fds[port_i].revents) {
            long n = drv_port_ready(&d->port, fds[port_i].revents, buf, sizeof buf, now_ms);
            if (n > 0)
                on_bytes(d, buf, (size_t)n);
        }
        /* the port lost, on a read or on a protocol's write: a half frame of
         * it never ends; the port (re)opened: a device that needs its
         * configuration or a first poll gets it */
        if (was_open && d->port.state != DRV_PORT_OPEN && d->p->reset)
            d->p->reset(d->state, &d->ctx);
        if (!was_open && d->port.state == DRV_PORT_OPEN && d->p->opened)
            d->p->opened(d->state, &d->ctx);
        was_open = d->port.state == DRV_PORT_OPEN;
        int64_t now = drv_clock_now(&d->clock);
        if (d->p->tick && now >= 0)
            d->p->tick(d->state, &d->ctx, now);
        if (now_ms >= next_status_ms) {
            drv_status_publish(&d->status, d->lcm, &d->ctx, &d->port, now < 0 ? 0 : now);
            next_status_ms += STATUS_MS;
            if (next_status_ms <= now_ms) /* after a stall: the next one in a second, no burst */
                next_status_ms = now_ms + STATUS_MS;
        }
    }
    return 0;
}

int drv_main(const drv_protocol *p, int argc, char **argv)
{
    driver d;
    memset(&d, 0, sizeof d);
    d.p = p;
    d.state = calloc(1, p->state_size ? p->state_size : 1);
    if (!d.state)
        return 1;
    int o = drv_options_parse(&d.opt, p, d.state, argc, argv);
    if (o) {
        free(d.state);
        return o == 1 ? 0 : 2;
    }
    snprintf(d.log_prefix, sizeof d.log_prefix, "%s: %s", p->program, p->device);
    snprintf(d.raw_channel, sizeof d.raw_channel, "%s.RAW.%s", d.opt.vehicle, p->device);
    if (d.opt.tcp) {
        char err[256];
        if (drv_port_tcp(&d.port, d.opt.tcp, d.log_prefix, err, sizeof err) < 0) {
            fprintf(stderr, "%s: %s\n", p->program, err);
            free(d.state);
            return 2;
        }
    } else {
        drv_port_serial(&d.port, d.opt.device_path, d.opt.baud, d.log_prefix);
    }
    d.lcm = lcm_create(d.opt.lcm_url);
    if (!d.lcm) {
        fprintf(stderr, "%s: cannot open LCM at %s\n", p->program, d.opt.lcm_url ? d.opt.lcm_url : "(default)");
        free(d.state);
        return 1;
    }
    int rc = 1;
    if (drv_clock_init(&d.clock, d.opt.clock, d.lcm) < 0) {
        fprintf(stderr, "%s: cannot subscribe to SIM.CLOCK\n", p->program);
        goto out;
    }
    drv_ctx_init(&d.ctx, p->program, d.opt.vehicle, p->device, lcm_sink, d.lcm);
    d.ctx.write = port_write;
    d.ctx.write_user = &d;
    if (p->init && p->init(d.state, &d.ctx) < 0)
        goto out;
    char err[256];
    if (drv_subs_init(&d.subs, d.lcm, p, d.state, &d.ctx, &d.clock, err, sizeof err) < 0) {
        fprintf(stderr, "%s: %s\n", p->program, err);
        goto out;
    }
    drv_status_init(&d.status);

    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal; /* no SA_RESTART: poll returns at once */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN); /* a TCP peer gone while we write: an error, not a death */

    rc = run(&d);
    int64_t now = drv_clock_now(&d.clock);
    if (p->finish && now >= 0)
        p->finish(d.state, &d.ctx, now);
    drv_status_publish(&d.status, d.lcm, &d.ctx, &d.port, now < 0 ? 0 : now);
    fprintf(stderr, "%s: %s: stopped: %lld bytes, %lld frames, %lld messages, %lld dropped, %lld reopens\n",
            p->program, p->device, (long long)d.port.bytes_read, (long long)d.ctx.frames_decoded,
            (long long)d.ctx.messages_published, (long long)d.ctx.reasons.total, (long long)d.port.reopens);
out:
    drv_subs_close(&d.subs, d.lcm);
    drv_clock_close(&d.clock, d.lcm);
    drv_port_close(&d.port);
    lcm_destroy(d.lcm);
    free(d.state);
    return rc;
}
