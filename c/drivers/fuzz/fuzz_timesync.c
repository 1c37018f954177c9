/* Fuzz entry point for auv-timesync's protocol (c/drivers/timesync): any bytes,
 * in reads cut by the input itself, through the driver's protocol. Every
 * SIM.CLOCK it publishes must decode, hold a valid time never below the one
 * before nor more than the time rule's jump above it unless a second sentence
 * confirmed the jump, and a warp in range (libFuzzer, or the project's driver
 * c/chasm/fuzz/fuzz_driver.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_sim_clock_t.h"
#include "common/lcm_rx.h"
#include "drivers/timesync/timesync.h"

static int64_t last_clock;
static int have_clock;

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz_timesync: broken: %s\n", what);
        abort();
    }
}

static void sink(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    (void)user;
    check(!strcmp(channel, "SIM.CLOCK"), "the clock's channel");
    auv_sim_clock_t m;
    check(rx_decode(type, data, len, &m) == 0, "a published clock decodes");
    check(tp_utime_valid(m.utime), "a valid time");
    check(!have_clock || m.utime >= last_clock, "never backwards");
    check(m.warp >= 0.0 && m.warp <= PAUVT_MAX_WARP && isfinite(m.warp), "a warp in range");
    check((m.mode == AUV_SIM_CLOCK_T_MODE_REALTIME) == (m.warp == 1.0), "the mode of the warp");
    check(m.term == 0 && !strcmp(m.server_id, "FUZZ-timelink"), "term and server");
    last_clock = m.utime;
    have_clock = 1;
    auv_sim_clock_t_decode_cleanup(&m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    timesync_state *s = calloc(1, sizeof *s);
    drv_ctx ctx;
    drv_ctx_init(&ctx, "fuzz_timesync", "FUZZ", "TIMESYNC", sink, NULL);
    ctx.quiet = 1;
    have_clock = 0;
    check(s && timesync_protocol.init(s, &ctx) == 0, "init");
    int64_t t = INT64_C(1700000000000000);
    unsigned cut = size ? data[0] : 3;
    for (size_t i = 0; i < size;) {
        size_t n = 1 + (cut + i) % 48;
        if (n > size - i)
            n = size - i;
        timesync_protocol.feed(s, &ctx, data + i, n, t += 10000);
        i += n;
    }
    check(ctx.frames_decoded == ctx.messages_published, "one clock per accepted sentence");
    free(s);
    return 0;
}
