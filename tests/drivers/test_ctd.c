/* Unit tests of auv-ctd's protocol (c/drivers/ctd): the SBE 49 manual's own
 * example scans in both engineering formats, the optional salinity and sound
 * velocity, what is not a scan, every refusal, PSS-78 and UNESCO depth against
 * their published check values, and the stream cut anywhere. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_ctd_t.h"
#include "common/lcm_rx.h"
#include "drivers/ctd/ctd.h"
#include "drivers/ctd/pss78.h"
#include "../harness/unit.h"

#define T0 INT64_C(1700000000000000)
#define MAX_SCANS 32

typedef struct {
    ctd_state s;
    drv_ctx ctx;
    auv_ctd_t scan[MAX_SCANS];
    int n;
} rig;

static void capture(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    rig *r = user;
    CHECK_STR(channel, "AUV1.CTD");
    if (r->n < MAX_SCANS) {
        auv_ctd_t *m = &r->scan[r->n++];
        CHECK(rx_decode(type, data, len, m) == 0);
        CHECK_STR(m->vehicle, "AUV1");
        auv_ctd_t_decode_cleanup(m);
        m->vehicle = NULL;
    }
}

static rig *rig_new(void)
{
    rig *r = calloc(1, sizeof *r);
    drv_ctx_init(&r->ctx, "test", "AUV1", "CTD", capture, r);
    r->ctx.quiet = 1;
    CHECK(ctd_protocol.init(&r->s, &r->ctx) == 0);
    return r;
}

static void feed(rig *r, const char *text, int64_t stamp)
{
    ctd_protocol.feed(&r->s, &r->ctx, (const uint8_t *)text, strlen(text), stamp);
}

static int64_t count(const rig *r, const char *reason) { return drv_reasons_get(&r->ctx.reasons, reason); }

static void test_ctd_manual_examples(void)
{
    rig *r = rig_new();
    /* OutputFormat=3 with OutputSal=N, OutputSV=N, and OutputFormat=1: the manual's scans */
    feed(r, "23.7658, 0.00019, 0.062\r\n3385C40F42FE0186DE\r\n", T0);
    CHECK(r->n == 2);
    for (int k = 0; k < 2; k++) {
        CHECK_NEAR(r->scan[k].temperature_c, 23.7658, 1e-9);
        CHECK_NEAR(r->scan[k].conductivity_s_per_m, 0.00019, 1e-9);
        CHECK_NEAR(r->scan[k].pressure_dbar, 0.062, 1e-9);
        CHECK(r->scan[k].valid && r->scan[k].utime == T0);
        CHECK(isnan(r->scan[k].salinity_psu));      /* fresh water: under PSS-78's 2 PSU */
        CHECK(isnan(r->scan[k].sound_speed_mps));   /* none sent, none made up */
    }
    /* sea water, with the instrument's salinity and sound velocity, or either alone */
    feed(r, "15.0000, 4.29140, 0.000, 35.0000, 1506.700\r\n", T0 + 1);
    feed(r, "14.9964, 4.29140, 0.000, 1506.700\r\n", T0 + 2);
    feed(r, "15.0000, 4.29140, 0.000, 34.9000\r\n", T0 + 3);
    CHECK(r->n == 5);
    CHECK_NEAR(r->scan[2].salinity_psu, 35.0, 1e-12);
    CHECK_NEAR(r->scan[2].sound_speed_mps, 1506.7, 1e-9);
    CHECK_NEAR(r->scan[3].sound_speed_mps, 1506.7, 1e-9);
    CHECK_NEAR(r->scan[3].salinity_psu, 35.0, 1e-4);   /* PSS-78 from C, T, p: 14.9964 degC ITS-90 is 15 IPTS-68 */
    CHECK_NEAR(r->scan[4].salinity_psu, 34.9, 1e-12);  /* the instrument's, not recomputed */
    CHECK(isnan(r->scan[4].sound_speed_mps));
    CHECK(r->ctx.frames_decoded == 5 && r->ctx.reasons.total == 0);
    free(r);
}

static void test_ctd_not_scans_and_refusals(void)
{
    rig *r = rig_new();
    /* the prompt, command echoes, the status text: passed over, nothing counted */
    feed(r, "S>\r\nS>Stop\r\n<Executed/>\r\nSBE 49 FastCAT V 1.3a SERIAL NO. 0001\r\n\r\n", T0);
    CHECK(r->n == 0 && r->ctx.reasons.total == 0);
    struct {
        const char *line, *reason;
    } cases[] = {
        {"0A53711BC7220C14C17D82", "raw counts"},          /* OutputFormat=0: needs calibration */
        {"676721, 7111.133, 791745, 2.4514", "raw counts"}, /* OutputFormat=2 */
        {"3385C40F42FE0186D", "bad length"},               /* a hex scan cut short */
        {"3385C40F42FE0186DE3385C40F42FE0186DE", "bad length"},
        {"23.7658, 0.00019", "bad field count"},
        {"23.7658, 0.00019, 0.062, 35.0, 1500.0, 7", "bad field count"},
        {"23.7658, 0.0x019, 0.062", "bad number"},
        {"23.7658,, 0.062", "bad number"},
        {"99.0000, 4.00000, 10.000", "out of range"},     /* no sea is 99 degC */
        {"15.0000, 14.00000, 10.000", "out of range"},    /* over the cell's 9 S/m */
        {"15.0000, 4.00000, 20000.000", "out of range"},
        {"15.0000, 4.00000, 10.000, 60.0000", "out of range"}, /* salinity */
        {"15.0000, 4.00000, 10.000, 35.0, 900.0", "out of range"},
        {"-nan, 4.0, 1.0", "bad number"},
        {"15.0000, 0x4, 10.000", "bad number"},          /* hex: strtod reads it, no SBE 49 writes it */
        {"1.5e1, 4.00000, 10.000", "bad number"},        /* an exponent: not the manual's format */
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        int64_t before = count(r, cases[k].reason);
        char line[160];
        snprintf(line, sizeof line, "%s\r\n", cases[k].line);
        feed(r, line, T0 + (int64_t)k);
        if (count(r, cases[k].reason) != before + 1)
            fprintf(stderr, "case %zu (%s): %s\n", k, cases[k].line, r->ctx.last_error);
        CHECK(count(r, cases[k].reason) == before + 1);
    }
    CHECK(r->n == 0);
    /* a line with no end runs past the maximum: one drop, and the next line is read */
    char endless[400];
    memset(endless, '1', sizeof endless - 1);
    endless[sizeof endless - 1] = 0;
    feed(r, endless, T0 + 100);
    feed(r, "\r\n15.0000, 4.00000, 10.000\r\n", T0 + 101);
    CHECK(count(r, "line too long") == 1 && r->n == 1);
    free(r);
}

static void test_ctd_stream_cut_anywhere(void)
{
    /* the same scans fed whole and a byte at a time give the same messages; a reset
     * (a lost port) forgets the half line */
    const char *text = "12.3456, 3.81234, 5.123\r\n0A53711BC7220C14C1\r\nS>\r\n16.0000, 4.40000, 2.000, 33.1\r\n";
    rig *a = rig_new(), *b = rig_new();
    feed(a, text, T0);
    for (const char *p = text; *p; p++) {
        char one[2] = {*p, 0};
        feed(b, one, T0);
    }
    CHECK(a->n == 3 && b->n == 3);
    for (int k = 0; k < 3; k++)
        CHECK(a->scan[k].temperature_c == b->scan[k].temperature_c &&
              a->scan[k].pressure_dbar == b->scan[k].pressure_dbar);
    /* lines ended by CR alone or LF alone are scans as well */
    rig *c = rig_new();
    feed(c, "12.3456, 3.81234, 5.123\r0A53711BC7220C14C1\nS>\r16.0000, 4.40000, 2.000, 33.1\r", T0);
    CHECK(c->n == 3 && c->ctx.reasons.total == 0);
    CHECK(c->scan[2].temperature_c == a->scan[2].temperature_c);
    free(c);
    feed(b, "12.3456, 3.81", T0);
    ctd_protocol.reset(&b->s, &b->ctx);
    feed(b, "234, 5.123\r\n", T0);
    CHECK(b->n == 3 && drv_reasons_get(&b->ctx.reasons, "bad number") + drv_reasons_get(&b->ctx.reasons, "bad field count") == 1);
    free(a);
    free(b);
}

static void test_ctd_pss78_and_depth(void)
{
    /* PSS-78's definition: standard seawater (S 35) at 15 degC IPTS-68, 0 dbar, is 4.2914 S/m */
    CHECK_NEAR(pss78_salinity(4.2914, 15.0 / 1.00024, 0.0), 35.0, 1e-6);
    /* UNESCO 1983's check value: R = 1.888091 at 40 degC (IPTS-68), 10000 dbar is S = 40.0000 */
    CHECK_NEAR(pss78_salinity(1.888091 * 4.2914, 40.0 / 1.00024, 10000.0), 40.0, 1e-4);
    CHECK(isnan(pss78_salinity(0.0, 10.0, 0.0)) && isnan(pss78_salinity(-1.0, 10.0, 0.0)));
    CHECK(isnan(pss78_salinity(4.0, NAN, 0.0)));
    /* UNESCO 1983's check value: 10000 dbar at 30 degrees latitude is 9712.653 m */
    CHECK_NEAR(pss78_depth(10000.0, 30.0), 9712.653, 1e-3);
    CHECK_NEAR(pss78_depth(0.0, 45.0), 0.0, 1e-12);
    /* about 0.99 m per dbar near the surface */
    CHECK(pss78_depth(10.0, 45.0) > 9.9 && pss78_depth(10.0, 45.0) < 10.0);
}

static void test_ctd_flags(void)
{
    ctd_state s = {0};
    char err[200];
    CHECK(ctd_set_latitude(&s, "91", err, sizeof err) == -1 && strstr(err, "--latitude"));
    CHECK(ctd_set_latitude(&s, "12.5", err, sizeof err) == 0 && s.latitude_deg == 12.5);
    CHECK(ctd_set_configure(&s, "0", err, sizeof err) == -1 && strstr(err, "1 (hex) or 3"));
    CHECK(ctd_set_configure(&s, "3", err, sizeof err) == 0 && s.configure == 3);
}

static const unit_test tests[] = {
    {"ctd_manual_examples", test_ctd_manual_examples},
    {"ctd_not_scans_and_refusals", test_ctd_not_scans_and_refusals},
    {"ctd_stream_cut_anywhere", test_ctd_stream_cut_anywhere},
    {"ctd_pss78_and_depth", test_ctd_pss78_and_depth},
    {"ctd_flags", test_ctd_flags},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
