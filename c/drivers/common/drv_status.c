#include "drivers/common/drv_status.h"

#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "auv/auv_driver_status_t.h"
#include "auv/auv_process_health_t.h"

static double wall_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static double cpu_s(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) * 1e-6;
}

void drv_status_init(drv_status *s)
{
    s->last_wall = wall_s();
    s->last_cpu = cpu_s();
}

void drv_status_publish(drv_status *s, lcm_t *lcm, const drv_ctx *ctx, const drv_port *port, int64_t utime)
{
    char channel[128];
    auv_driver_status_t m;
    memset(&m, 0, sizeof m);
    m.utime = utime;
    m.vehicle = (char *)ctx->vehicle;
    m.device = (char *)ctx->device;
    m.port = (char *)port->name;
    m.port_open = port->state == DRV_PORT_OPEN;
    m.reopens = port->reopens;
    m.bytes_read = port->bytes_read;
    m.bytes_written = port->bytes_written;
    m.frames_decoded = ctx->frames_decoded;
    m.messages_published = ctx->messages_published;
    m.last_frame_utime = ctx->last_frame_utime;
    m.n_reasons = (int16_t)ctx->reasons.n;
    char *names[DRV_MAX_REASONS];
    int64_t counts[DRV_MAX_REASONS];
    for (int i = 0; i < ctx->reasons.n; i++) {
        names[i] = (char *)ctx->reasons.name[i];
        counts[i] = ctx->reasons.count[i];
    }
    m.reason = names;
    m.reason_count = counts;
    /* the newest of a drop and a port error */
    m.last_error = (char *)(port->last_error[0] && port->state != DRV_PORT_OPEN ? port->last_error : ctx->last_error);
    snprintf(channel, sizeof channel, "%s.DRIVER.%s", ctx->vehicle, ctx->device);
    auv_driver_status_t_publish(lcm, channel, &m);

    double w = wall_s(), c = cpu_s();
    auv_process_health_t h;
    memset(&h, 0, sizeof h);
    h.utime = utime;
    h.vehicle = (char *)ctx->vehicle;
    h.process = (char *)ctx->program;
    h.pid = (int32_t)getpid();
    h.messages_received = ctx->frames_decoded;
    h.decode_errors = ctx->reasons.total;
    h.queue_overflows = 0;
    h.cpu_load = w > s->last_wall ? (c - s->last_cpu) / (w - s->last_wall) : 0.0;
    s->last_wall = w;
    s->last_cpu = c;
    snprintf(channel, sizeof channel, "%s.HEALTH", ctx->vehicle);
    auv_process_health_t_publish(lcm, channel, &h);
}
