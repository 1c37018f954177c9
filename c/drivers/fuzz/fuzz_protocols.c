/* libFuzzer-style entry point for every driver's protocol linked in (the GPS
 * and its NMEA framing first): the input is a byte stream, cut into reads of
 * sizes taken from the input itself, with time passing between them and a
 * lost port in the middle. Each message a protocol publishes must decode
 * again and carry a stamp it was given; a GPS fix must hold in-range values.
 * A crash, a sanitizer report or a broken check aborts. Driven by
 * c/chasm/fuzz/fuzz_driver.c (`make fuzz`), or by libFuzzer itself. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_gps_fix_t.h"
#include "common/lcm_rx.h"
#include "drivers/common/drv_protocol.h"

#define FUZZ_T0 INT64_C(1700000000000000)

static int64_t max_stamp;
static const drv_protocol *cur_proto;
static const uint8_t *cur_data;
static size_t cur_size;

/* A broken check is no sanitizer report: the input is written here, then abort. */
static void check(int ok, const char *what)
{
    if (ok)
        return;
    fprintf(stderr, "drivers_fuzz: broken: %s; input written to drivers-broken.bin\n", what);
    FILE *f = fopen("drivers-broken.bin", "wb");
    if (f) {
        fwrite(cur_data, 1, cur_size, f);
        fclose(f);
    }
    abort();
}

static void sink(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    (void)user;
    (void)channel;
    void *msg = calloc(1, type->struct_size);
    check(msg && rx_decode(type, data, len, msg) == 0, "a published message decodes");
    int64_t utime = *(const int64_t *)msg; /* every type starts with utime */
    /* a link's own time (a clock, a framed message) is the link's, checked by the protocol */
    check(cur_proto->link_time || (utime >= FUZZ_T0 && utime <= max_stamp), "a stamp the protocol was given");
    if (!strcmp(type->lcm_name, "auv.gps_fix_t")) {
        const auv_gps_fix_t *m = msg;
        check(fabs(m->latitude_deg) <= 90.0 && fabs(m->longitude_deg) <= 180.0, "a position on the earth");
        check(m->satellites >= -1 && m->satellites <= 99, "satellites");
        check(isnan(m->hdop) || (m->hdop >= 0.0 && m->hdop <= 100.0), "hdop");
        check(m->horizontal_sigma_m > 0.0 && isfinite(m->horizontal_sigma_m), "sigma");
        check(m->quality >= 1 && m->quality <= 8 && m->fix_type >= 2, "a fix");
        check(m->utc_utime == -1 || m->utc_utime >= 631152000000000, "a UTC after --min-year (1990)");
    }
    type->info()->decode_cleanup(msg);
    free(msg);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cur_data = data;
    cur_size = size;
    for (int k = 0; k < drv_count(); k++) {
        const drv_protocol *p = drv_at(k);
        cur_proto = p;
        void *state = calloc(1, p->state_size ? p->state_size : 1);
        drv_ctx ctx;
        drv_ctx_init(&ctx, "drivers_fuzz", "FUZZ", p->device, sink, NULL);
        ctx.quiet = 1;
        check(state && (!p->init || p->init(state, &ctx) == 0), "init");
        int64_t t = FUZZ_T0;
        size_t i = 0;
        unsigned cut = size ? data[0] : 7;
        while (i < size) {
            /* read sizes 1 .. 64 from the input's own bytes, 0.05 .. 0.8 s apart */
            size_t n = 1 + (cut + i) % 64;
            if (n > size - i)
                n = size - i;
            t += 50000 * (1 + (int64_t)((data[i] ^ cut) % 16));
            max_stamp = t;
            if (p->tick)
                p->tick(state, &ctx, t);
            p->feed(state, &ctx, data + i, n, t);
            i += n;
            if (p->reset && i > size / 2 && i - n <= size / 2)
                p->reset(state, &ctx);
        }
        if (p->finish)
            p->finish(state, &ctx, t);
        check(ctx.reasons.total >= 0 && ctx.frames_decoded >= 0, "counters");
        free(state);
    }
    return 0;
}
