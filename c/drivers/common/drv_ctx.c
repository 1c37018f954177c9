#include "drivers/common/drv_ctx.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void drv_ctx_init(drv_ctx *c, const char *program, const char *vehicle, const char *device, drv_sink_fn sink,
                  void *sink_user)
{
    memset(c, 0, sizeof *c);
    c->program = program;
    c->vehicle = vehicle;
    c->device = device;
    c->sink = sink;
    c->sink_user = sink_user;
    c->last_frame_utime = -1;
    drv_reasons_init(&c->reasons);
}

void drv_log(const drv_ctx *c, const char *fmt, ...)
{
    if (c->quiet)
        return;
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    fprintf(stderr, "%s: %s: %s\n", c->program, c->device, line);
}

void drv_drop(drv_ctx *c, const char *reason, const char *detail_fmt, ...)
{
    char detail[200];
    va_list ap;
    va_start(ap, detail_fmt);
    vsnprintf(detail, sizeof detail, detail_fmt, ap);
    va_end(ap);
    snprintf(c->last_error, sizeof c->last_error, "%s: %s", reason, detail);
    if (drv_reasons_count(&c->reasons, reason))
        drv_log(c, "dropped: %s (%s); further drops of this kind are only counted", reason, detail);
}

void drv_frame_ok(drv_ctx *c, int64_t stamp)
{
    c->frames_decoded++;
    c->last_frame_utime = stamp;
}

/* Encodes msg and hands it to the sink on channel. */
static int publish_on(drv_ctx *c, const char *channel, const auv_type_entry_t *type, const void *msg)
{
    const lcm_type_info_t *info = type->info();
    int len = (int)info->encoded_size(msg);
    uint8_t stackbuf[4096];
    uint8_t *buf = len <= (int)sizeof stackbuf ? stackbuf : malloc((size_t)len);
    if (!buf || info->encode(buf, 0, len, msg) != len) {
        if (buf != stackbuf)
            free(buf);
        drv_log(c, "cannot encode a %s", type->lcm_name);
        return -1;
    }
    if (c->sink)
        c->sink(c->sink_user, channel, type, buf, len);
    c->messages_published++;
    if (buf != stackbuf)
        free(buf);
    return 0;
}

int drv_publish(drv_ctx *c, const char *topic, const auv_type_entry_t *type, const void *msg)
{
    char channel[128];
    snprintf(channel, sizeof channel, "%s.%s", c->vehicle, topic);
    return publish_on(c, channel, type, msg);
}

int drv_publish_global(drv_ctx *c, const char *channel, const auv_type_entry_t *type, const void *msg)
{
    return publish_on(c, channel, type, msg);
}

void drv_publish_encoded(drv_ctx *c, const char *topic, const auv_type_entry_t *type, const void *data, int len)
{
    char channel[128];
    snprintf(channel, sizeof channel, "%s.%s", c->vehicle, topic);
    if (c->sink)
        c->sink(c->sink_user, channel, type, data, len);
    c->messages_published++;
}

int drv_write(drv_ctx *c, const uint8_t *data, size_t n) { return c->write ? c->write(c->write_user, data, n) : -1; }
