/* Unit tests of auv-modem's protocol (c/drivers/modem/modem_protocol.c) on the
 * framework without a port: what it writes at opening and for a modem_tx_t,
 * a frame sent and echoed, a frame received with its SNR and its stamp, the
 * status's counts and period, each refusal as a reason, and the flags. The
 * bridge's own exchanges are test_mm.c's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_modem_rx_t.h"
#include "auv/auv_modem_status_t.h"
#include "auv/auv_modem_tx_t.h"
#include "common/lcm_rx.h"
#include "drivers/modem/modem.h"
#include "../harness/unit.h"

#define T0 INT64_C(1700000000000000)
#define MAX_RX 8

typedef struct {
    modem_state s;
    drv_ctx ctx;
    char written[4096];
    size_t n_written;
    auv_modem_rx_t rx[MAX_RX];
    int64_t rx_utime[MAX_RX];
    int n_rx;
    auv_modem_status_t status; /* the newest */
    int n_status;
} rig;

static void capture(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    rig *r = user;
    if (!strcmp(channel, "AUV1.MODEM_RX")) {
        CHECK(r->n_rx < MAX_RX);
        if (r->n_rx < MAX_RX)
            CHECK(rx_decode(type, data, len, &r->rx[r->n_rx++]) == 0);
    } else {
        CHECK_STR(channel, "AUV1.MODEM_STATUS");
        if (r->n_status)
            auv_modem_status_t_decode_cleanup(&r->status);
        CHECK(rx_decode(type, data, len, &r->status) == 0);
        r->n_status++;
    }
}

static int capture_write(void *user, const uint8_t *data, size_t n)
{
    rig *r = user;
    if (r->n_written + n < sizeof r->written) {
        memcpy(r->written + r->n_written, data, n);
        r->n_written += n;
        r->written[r->n_written] = 0;
    }
    return 0;
}

static int set_flag(rig *r, const char *name, const char *value, char *err, size_t n)
{
    for (const drv_flag *f = modem_protocol.flags; f->name; f++)
        if (!strcmp(f->name, name))
            return f->set(&r->s, value, err, n);
    return -2;
}

static rig *rig_new(int with_port, const char *const *flags)
{
    rig *r = calloc(1, sizeof *r);
    drv_ctx_init(&r->ctx, "test", "AUV1", "MODEM", capture, r);
    r->ctx.quiet = 1;
    if (with_port) {
        r->ctx.write = capture_write;
        r->ctx.write_user = r;
    }
    char err[200];
    for (int i = 0; flags && flags[i]; i += 2)
        CHECK(set_flag(r, flags[i], flags[i + 1], err, sizeof err) == 0);
    return r;
}

static void rig_free(rig *r)
{
    for (int i = 0; i < r->n_rx; i++)
        auv_modem_rx_t_decode_cleanup(&r->rx[i]);
    if (r->n_status)
        auv_modem_status_t_decode_cleanup(&r->status);
    free(r);
}

/* "$" body "*hh\r\n" fed at stamp */
static void modem_says(rig *r, const char *body, int64_t stamp)
{
    char line[700];
    CHECK(nmea_format(line, sizeof line, body) > 0);
    modem_protocol.tick(&r->s, &r->ctx, stamp);
    modem_protocol.feed(&r->s, &r->ctx, (const uint8_t *)line, strlen(line), stamp);
}

static void send_frame(rig *r, const char *vehicle, const char *dst, int n_bytes, int64_t now)
{
    uint8_t payload[300];
    for (int i = 0; i < n_bytes; i++)
        payload[i] = (uint8_t)(0xA0 + i);
    auv_modem_tx_t m = {.utime = now, .vehicle = (char *)vehicle, .dst_vehicle = (char *)dst, .seq = 7,
                        .kind = 2, .n_bytes = (int16_t)n_bytes, .payload = payload};
    modem_protocol.subscriptions[0].handler(&r->s, &r->ctx, &m, now);
}

static void test_send_and_echo(void)
{
    static const char *const flags[] = {"--table", "AUV1=1,AUV2=2", NULL};
    rig *r = rig_new(1, flags);
    CHECK_STR(modem_protocol.subscriptions[0].suffix, "MODEM_TX");
    CHECK(modem_protocol.init(&r->s, &r->ctx) == 0);
    modem_protocol.opened(&r->s, &r->ctx);
    CHECK_STR(r->written, "$CCCFG,SRC,1*31\r\n$CCCFG,CST,1*37\r\n$CCCFQ,SRC*3A\r\n");
    r->n_written = 0;
    modem_protocol.tick(&r->s, &r->ctx, T0);
    CHECK(r->n_status == 1 && r->status.modem_address == 1 && r->status.rate == 0);
    send_frame(r, "", "AUV2", 3, T0 + 1000);
    CHECK_STR(r->written, "$CCCYC,0,1,2,0,0,1*5B\r\n");
    CHECK(r->status.busy_until_utime == T0 + 1000 + 5000000);
    r->n_written = 0;
    modem_says(r, "CACYC,0,1,2,0,0,1", T0 + 2000);
    modem_says(r, "CADRQ,000102,1,2,0,32,1", T0 + 3000);
    CHECK_STR(r->written, "$CCTXD,1,2,0,A0A1A2*09\r\n");
    modem_says(r, "CATXD,1,2,0,3", T0 + 4000);
    CHECK(r->status.sent == 1 && r->status.busy_until_utime == 0 && r->status.utime == T0 + 4000);
    CHECK(r->ctx.frames_decoded == 3 && r->ctx.reasons.total == 0);
    rig_free(r);
}

static void test_receive_with_snr(void)
{
    static const char *const flags[] = {"--table", "AUV1=1,AUV2=2,AUV3=3", NULL};
    rig *r = rig_new(1, flags);
    CHECK(modem_protocol.init(&r->s, &r->ctx) == 0);
    modem_says(r, "CACYC,0,2,1,1,0,1", T0);
    modem_says(r, "CARXD,2,1,0,1,0102FF", T0 + 5000);
    CHECK(r->n_rx == 0); /* held for its CACST */
    modem_says(r,
               "CACST,0,000102.0000,0,1000,20,100,100,70,0,0,0,0,1,2,1,0,1,1,0,12.5,14.0,13.0,0,-20,100,0.0,50,25000,"
               "5000",
               T0 + 900000);
    CHECK(r->n_rx == 1);
    auv_modem_rx_t *m = &r->rx[0];
    CHECK(m->utime == T0 + 5000); /* the CARXD's receive time, not the CACST's */
    CHECK_STR(m->vehicle, "AUV1");
    CHECK_STR(m->src_vehicle, "AUV2");
    CHECK_STR(m->dst_vehicle, "AUV1");
    CHECK(m->kind == 2 && m->seq == 1 && m->tx_utime == 0 && isnan(m->range_m));
    CHECK(fabs(m->snr_db - 14.0) < 1e-9);
    CHECK(m->n_bytes == 3 && m->payload[0] == 1 && m->payload[2] == 0xFF);
    CHECK(r->status.received == 1);
    /* a broadcast without CACST: delivered after the hold, SNR NaN */
    modem_says(r, "CARXD,3,0,0,1,AB", T0 + 1000000);
    modem_protocol.tick(&r->s, &r->ctx, T0 + 3100000);
    CHECK(r->n_rx == 2 && r->rx[1].utime == T0 + 1000000 && isnan(r->rx[1].snr_db));
    CHECK_STR(r->rx[1].dst_vehicle, "");
    CHECK_STR(r->rx[1].src_vehicle, "AUV3");
    rig_free(r);
}

static void test_refusals_by_reason(void)
{
    static const char *const flags[] = {"--table", "AUV1=1,AUV2=2", NULL};
    rig *r = rig_new(1, flags);
    CHECK(modem_protocol.init(&r->s, &r->ctx) == 0);
    send_frame(r, "", "AUV2", 33, T0);
    CHECK(drv_reasons_get(&r->ctx.reasons, "frame over the rate's size") == 1);
    CHECK(r->status.refused_size == 1 && r->status.last_refused_seq == 7);
    CHECK(strstr(r->status.last_refusal, "33 bytes") != NULL);
    send_frame(r, "AUV2", "", 4, T0); /* another vehicle's frame */
    CHECK(drv_reasons_get(&r->ctx.reasons, "invalid frame") == 1 && r->status.refused_invalid == 1);
    send_frame(r, "", "NOBODY", 4, T0);
    CHECK(drv_reasons_get(&r->ctx.reasons, "invalid frame") == 2);
    send_frame(r, "", "", 4, T0);
    send_frame(r, "", "", 4, T0 + 1); /* the first is on its way */
    CHECK(drv_reasons_get(&r->ctx.reasons, "busy") == 1 && r->status.refused_rate == 1);
    modem_protocol.tick(&r->s, &r->ctx, T0 + 6000000); /* no CADRQ */
    CHECK(drv_reasons_get(&r->ctx.reasons, "modem timeout") == 1 && r->status.timeouts == 1);
    const char bad[] = "$CATXD,1,0,0,4*00\r\n";
    modem_protocol.feed(&r->s, &r->ctx, (const uint8_t *)bad, strlen(bad), T0 + 7000000);
    CHECK(drv_reasons_get(&r->ctx.reasons, "bad checksum") == 1);
    modem_says(r, "CAERR,000102,NMEA,3,bad address", T0 + 7100000);
    CHECK(drv_reasons_get(&r->ctx.reasons, "modem error") == 1 && r->status.modem_errors == 1);
    modem_says(r, "CARXD,9,1,0,1,AB", T0 + 7200000); /* from an address not in the table */
    CHECK(drv_reasons_get(&r->ctx.reasons, "received frame dropped") == 1 && r->status.rx_dropped == 1);
    modem_says(r, "CARXD,2,1,0,1,ABC", T0 + 7300000);
    CHECK(drv_reasons_get(&r->ctx.reasons, "odd hex length") == 1);
    CHECK(r->ctx.reasons.total == 9);
    rig_free(r);
}

static void test_status_once_a_second(void)
{
    static const char *const flags[] = {"--table", "AUV1=1", NULL};
    rig *r = rig_new(1, flags);
    CHECK(modem_protocol.init(&r->s, &r->ctx) == 0);
    for (int64_t t = 0; t <= 3000000; t += 100000)
        modem_protocol.tick(&r->s, &r->ctx, T0 + t);
    CHECK(r->n_status == 4 && r->status.utime == T0 + 3000000);
    modem_says(r, "CAREV,000102,AUV,0.94.0.4", T0 + 3050000);
    CHECK(r->n_status == 5 && r->status.heartbeat_utime == T0 + 3050000);
    CHECK_STR(r->status.revision, "0.94.0.4");
    rig_free(r);
}

static void test_flags(void)
{
    char err[200];
    rig *r = rig_new(1, NULL);
    CHECK(set_flag(r, "--table", "AUV1=1,AUV2=200", err, sizeof err) == -1);
    CHECK(strstr(err, "--table wants") != NULL && strstr(err, "1..127") != NULL);
    CHECK(set_flag(r, "--table", "AUV1", err, sizeof err) == -1);
    CHECK(set_flag(r, "--rate", "6", err, sizeof err) == -1 && strstr(err, "--rate wants"));
    CHECK(set_flag(r, "--answer-timeout", "0", err, sizeof err) == -1);
    CHECK(set_flag(r, "--kind", "2", err, sizeof err) == 0);
    CHECK(modem_protocol.init(&r->s, &r->ctx) == -1); /* a port and no table */
    rig_free(r);
    r = rig_new(1, NULL);
    CHECK(set_flag(r, "--table", "AUV2=2", err, sizeof err) == 0);
    CHECK(modem_protocol.init(&r->s, &r->ctx) == -1); /* this vehicle is not in it */
    rig_free(r);
    r = rig_new(0, NULL); /* the replay, the fuzzer: no device, no table needed */
    CHECK(modem_protocol.init(&r->s, &r->ctx) == 0);
    modem_says(r, "CARXD,2,0,0,1,AB", T0); /* without the table no sender has a name */
    modem_protocol.finish(&r->s, &r->ctx, T0 + 1);
    CHECK(r->n_rx == 0 && drv_reasons_get(&r->ctx.reasons, "received frame dropped") == 1);
    rig_free(r);
}

static const unit_test tests[] = {
    {"modem_send_and_echo", test_send_and_echo},
    {"modem_receive_with_snr", test_receive_with_snr},
    {"modem_refusals_by_reason", test_refusals_by_reason},
    {"modem_status_once_a_second", test_status_once_a_second},
    {"modem_flags", test_flags},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
