/* The frontseat fuzz targets' one input (fuzz_iver3.c, fuzz_bluefin.c): each
 * gives its protocol, the checks of what auv-frontseat publishes (sink) and of
 * what it writes to the frontseat (on_write); this drives the core with the
 * input: the frontseat's bytes in reads the input cuts, ticks the input
 * spaces, and setpoints made of the input's bytes (any doubles, NaN and
 * infinities included) between them. Limits: --max-depth 40, --max-speed 2. */
#ifndef DRIVERS_FUZZ_FRONTSEAT_H
#define DRIVERS_FUZZ_FRONTSEAT_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frontseat/frontseat.h"

static double fuzz_fs_take_double(const uint8_t *data, size_t size, size_t *i)
{
    double d = 0.0;
    if (*i + sizeof d <= size) {
        memcpy(&d, data + *i, sizeof d);
        *i += sizeof d;
    }
    return d;
}

static void fuzz_fs_set(fs_state *fs, const char *flag, const char *value)
{
    char err[128];
    for (const drv_flag *f = frontseat_protocol.flags; f->name; f++)
        if (!strcmp(f->name, flag) && f->set(fs, value, err, sizeof err) != 0) {
            fprintf(stderr, "fuzz frontseat: %s %s refused: %s\n", flag, value, err);
            abort();
        }
}

static int fuzz_frontseat_one(const char *program, const char *protocol, drv_sink_fn sink, drv_write_fn on_write,
                              const uint8_t *data, size_t size)
{
    fs_state *fs = calloc(1, sizeof *fs);
    drv_ctx ctx;
    drv_ctx_init(&ctx, program, "FUZZ", "FRONTSEAT", sink, NULL);
    ctx.quiet = 1;
    ctx.write = on_write;
    fuzz_fs_set(fs, "--protocol", protocol);
    fuzz_fs_set(fs, "--max-depth", "40");
    fuzz_fs_set(fs, "--max-speed", "2");
    fuzz_fs_set(fs, "--origin", "41.5,-70.7");
    if (frontseat_protocol.init(fs, &ctx) != 0) {
        fprintf(stderr, "%s: broken: init\n", program);
        abort();
    }
    int64_t t = INT64_C(1700000000000000);
    unsigned cut = size ? data[0] : 5;
    for (size_t i = 0; i < size;) {
        t += 20000 * (1 + (int64_t)((data[i] ^ cut) % 64));
        frontseat_protocol.tick(fs, &ctx, t);
        if ((data[i] & 0x1f) == 0x1f) { /* a setpoint of the input's bytes */
            i++;
            auv_setpoint_t sp;
            memset(&sp, 0, sizeof sp);
            sp.utime = t - (int64_t)(i % 3) * 1000000;
            sp.vertical_mode = (int8_t)(i % 4);
            sp.speed_mode = (int8_t)((i / 4) % 3);
            sp.heading_rad = fuzz_fs_take_double(data, size, &i);
            sp.depth_m = fuzz_fs_take_double(data, size, &i);
            sp.altitude_m = fuzz_fs_take_double(data, size, &i);
            sp.speed_mps = fuzz_fs_take_double(data, size, &i);
            frontseat_protocol.subscriptions[0].handler(fs, &ctx, &sp, t);
            continue;
        }
        size_t n = 1 + (cut + i) % 48;
        if (n > size - i)
            n = size - i;
        frontseat_protocol.feed(fs, &ctx, data + i, n, t);
        i += n;
    }
    free(fs);
    return 0;
}

#endif
