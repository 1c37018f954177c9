/* Unit tests of auv-gps's protocol (c/drivers/gps): published example
 * sentences, every talker, the epoch grouping, the stamp and UTC rules, each
 * refusal reason, absurd values with valid checksums, and the hostile corpus
 * of tests/drivers/corpus/gps/ (each file: the stream, and the counts it must
 * give). */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_gps_fix_t.h"
#include "common/lcm_rx.h"
#include "drivers/gps/gps.h"
#include "../harness/unit.h"

#define T0 INT64_C(1700000000000000)
#define MAX_FIXES 64

typedef struct {
    gps_state g;
    drv_ctx ctx;
    auv_gps_fix_t fix[MAX_FIXES];
    int n;
} rig;

static void capture(void *user, const char *channel, const auv_type_entry_t *type, const void *data, int len)
{
    rig *r = user;
    CHECK_STR(channel, "AUV1.GPS");
    if (r->n < MAX_FIXES) {
        auv_gps_fix_t *m = &r->fix[r->n++];
        CHECK(rx_decode(type, data, len, m) == 0);
        CHECK_STR(m->vehicle, "AUV1");
        auv_gps_fix_t_decode_cleanup(m); /* frees the string: the tests read only numbers */
        m->vehicle = NULL;
    }
}

static rig *rig_new(const char *const *flags)
{
    rig *r = calloc(1, sizeof *r);
    drv_ctx_init(&r->ctx, "test", "AUV1", "GPS", capture, r);
    r->ctx.quiet = 1;
    char err[200];
    for (int i = 0; flags && flags[i]; i += 2)
        for (const drv_flag *f = gps_protocol.flags; f->name; f++)
            if (!strcmp(f->name, flags[i]))
                CHECK(f->set(&r->g, flags[i + 1], err, sizeof err) == 0);
    CHECK(gps_protocol.init(&r->g, &r->ctx) == 0);
    return r;
}

static void feed(rig *r, const char *text, int64_t stamp)
{
    gps_protocol.tick(&r->g, &r->ctx, stamp);
    gps_protocol.feed(&r->g, &r->ctx, (const uint8_t *)text, strlen(text), stamp);
}

/* "$" body "*hh\r\n" */
static const char *sentence(const char *body)
{
    static char buf[8][160];
    static int k;
    char *out = buf[k++ % 8];
    CHECK(nmea_format(out, 160, body) > 0);
    return out;
}

static int64_t count(const rig *r, const char *reason) { return drv_reasons_get(&r->ctx.reasons, reason); }

static void test_published_examples(void)
{
    /* the classic GGA/RMC/GSA/VTG/ZDA examples, checksums as published: the
     * RMC's 1994 date is taken by default */
    rig *r = rig_new((const char *const[]){"--origin", "48.1,11.5", NULL});
    feed(r, "$GPGSA,A,3,04,05,,09,12,,,24,,,,,2.5,1.3,2.1*39\r\n", T0);
    feed(r, "$GPVTG,054.7,T,034.4,M,005.5,N,010.2,K*48\r\n", T0 + 10000);
    feed(r, "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n", T0 + 20000);
    CHECK(r->n == 0); /* waiting for the epoch's RMC */
    feed(r, "$GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A\r\n", T0 + 30000);
    CHECK(r->n == 1);
    const auv_gps_fix_t *m = &r->fix[0];
    CHECK(m->utime == T0 + 20000); /* the receive time of the epoch's first sentence */
    CHECK_NEAR(m->latitude_deg, 48 + 7.038 / 60, 1e-12);
    CHECK_NEAR(m->longitude_deg, 11 + 31.0 / 60, 1e-12);
    CHECK(m->quality == 1 && m->satellites == 8 && m->fix_type == AUV_GPS_FIX_T_FIX_3D);
    CHECK_NEAR(m->hdop, 0.9, 1e-12);
    CHECK_NEAR(m->horizontal_sigma_m, 2.0 * 0.9, 1e-12);
    CHECK_NEAR(m->altitude_m, 545.4, 1e-9);
    CHECK_NEAR(m->speed_mps, 22.4 * 1852.0 / 3600.0, 1e-9);
    CHECK_NEAR(m->course_deg, 84.4, 1e-12);
    CHECK_NEAR(m->pdop, 2.5, 1e-12);
    CHECK_NEAR(m->vdop, 2.1, 1e-12);
    CHECK(m->utc_utime == (nmea_unix_day(1994, 3, 23) * 86400 + 12 * 3600 + 35 * 60 + 19) * INT64_C(1000000));
    /* north/east as python/sim/geo.py: 1 minute of latitude is about 1853 m there */
    CHECK_NEAR(m->north_m, 1923.6262274946, 1e-6); /* python/sim/geo.py's number */
    CHECK_NEAR(m->east_m, 1241.350360046177, 1e-6);
    CHECK(r->ctx.frames_decoded == 4 && r->ctx.reasons.total == 0);
    /* ZDA gives the date to a GGA-only stream */
    feed(r, "$GPZDA,201530.00,04,07,2002,00,00*60\r\n", T0 + 1000000);
    feed(r, sentence("GPGGA,201531.00,4807.038,N,01131.000,E,2,12,1.5,10.0,M,46.9,M,,"), T0 + 2000000);
    feed(r, sentence("GPGGA,201532.00,4807.038,N,01131.000,E,2,12,1.5,10.0,M,46.9,M,,"), T0 + 3000000);
    /* the first GGA-only epoch waits for an RMC that never comes; closed by
     * the next one, then the receiver is known to send GGA alone */
    CHECK(r->n == 3);
    CHECK(r->fix[1].utc_utime == (nmea_unix_day(2002, 7, 4) * 86400 + 20 * 3600 + 15 * 60 + 31) * INT64_C(1000000));
    CHECK(r->fix[2].utime == T0 + 3000000 && r->fix[2].quality == 2);
    CHECK(isnan(r->fix[2].speed_mps)); /* no RMC, and the VTG is too old */
    free(r);
}

static void test_each_talker(void)
{
    const char *talkers[] = {"GP", "GN", "GL", "GA", "GB", "BD"};
    for (size_t k = 0; k < sizeof talkers / sizeof talkers[0]; k++) {
        rig *r = rig_new(NULL);
        char body[160];
        snprintf(body, sizeof body, "%sGGA,010203.50,3530.0000,S,17410.0000,W,1,10,0.8,3.0,M,,M,,", talkers[k]);
        feed(r, sentence(body), T0);
        snprintf(body, sizeof body, "%sRMC,010203.50,A,3530.0000,S,17410.0000,W,1.0,359.9,150724,,,A", talkers[k]);
        feed(r, sentence(body), T0 + 5000);
        CHECK(r->n == 1);
        CHECK_NEAR(r->fix[0].latitude_deg, -35.5, 1e-12);
        CHECK_NEAR(r->fix[0].longitude_deg, -(174 + 10.0 / 60), 1e-12);
        CHECK(isnan(r->fix[0].north_m)); /* no --origin */
        CHECK(r->fix[0].utc_utime ==
              (nmea_unix_day(2024, 7, 15) * 86400 + 3600 + 2 * 60 + 3) * INT64_C(1000000) + 500000);
        free(r);
    }
    /* a GGA from a talker that is no GNSS receiver: valid, not ours, ignored */
    rig *r = rig_new(NULL);
    feed(r, sentence("HEGGA,010203,3530.0000,S,17410.0000,W,1,10,0.8,3.0,M,,M,,"), T0);
    gps_protocol.finish(&r->g, &r->ctx, T0 + 1000000);
    CHECK(r->ctx.reasons.total == 0 && r->n == 0 && r->ctx.frames_decoded == 1);
    free(r);
}

static void test_absurd_values_refused(void)
{
    static const struct {
        const char *body, *reason;
    } cases[] = {
        {"GPGGA,123519,20000.000,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,", "bad latitude"}, /* 200 degrees */
        {"GPGGA,123519,9100.000,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,", "bad latitude"},  /* 91 degrees */
        {"GPGGA,123519,4807.038,N,19131.000,E,1,08,0.9,545.4,M,46.9,M,,", "bad longitude"},
        {"GPGGA,123519,4807.038,X,01131.000,E,1,08,0.9,545.4,M,46.9,M,,", "bad latitude"},
        {"GPGGA,123519,4807.038,N,,,1,08,0.9,545.4,M,46.9,M,,", "missing position"},
        {"GPGGA,123519,,,,,1,08,0.9,545.4,M,46.9,M,,", "missing position"},
        {"GPGGA,253519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,", "bad time"},
        {"GPGGA,123519,4807.038,N,01131.000,E,9,08,0.9,545.4,M,46.9,M,,", "bad fix quality"},
        {"GPGGA,123519,4807.038,N,01131.000,E,1,100,0.9,545.4,M,46.9,M,,", "bad satellites"},
        {"GPGGA,123519,4807.038,N,01131.000,E,1,-3,0.9,545.4,M,46.9,M,,", "bad satellites"},
        {"GPGGA,123519,4807.038,N,01131.000,E,1,08,-0.9,545.4,M,46.9,M,,", "bad hdop"},
        {"GPGGA,123519,4807.038,N,01131.000,E,1,08,1e3,545.4,M,46.9,M,,", "bad hdop"},
        {"GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,99999.0,M,46.9,M,,", "bad altitude"},
        {"GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,F,46.9,M,,", "bad altitude"},
        {"GPGGA,123519,4807.038,N,01131.000,E,1", "too few fields"},
        {"GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230380,003.1,W", "date out of range"}, /* 1980 */
        {"GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230389,003.1,W", "date out of range"}, /* 1989 */
        {"GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,310224,003.1,W", "bad date"},
        {"GPRMC,123519,X,4807.038,N,01131.000,E,022.4,084.4,230324,003.1,W", "bad status"},
        {"GPRMC,123519,A,4807.038,N,01131.000,E,2000.0,084.4,230324,003.1,W", "bad speed"},
        {"GPRMC,123519,A,4807.038,N,01131.000,E,-1.0,084.4,230324,003.1,W", "bad speed"},
        {"GPRMC,123519,A,4807.038,N,01131.000,E,022.4,400.0,230324,003.1,W", "bad course"},
        {"GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230324,003.1,W,AD", "bad mode"},
        {"GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230324,003.1,W,1", "bad mode"},
        {"GPRMC,123519,A,,,,,022.4,084.4,230324,003.1,W", "missing position"},
        {"GPVTG,054.7,T,034.4,M,-5.5,N,010.2,K", "bad speed"},
        {"GPVTG,554.7,T,034.4,M,005.5,N,010.2,K", "bad course"},
        {"GPGSA,A,4,04,05,,09,12,,,24,,,,,2.5,1.3,2.1", "bad fix mode"},
        {"GPGSA,A,3,04,05,,09,12,,,24,,,,,2.5,-1.3,2.1", "bad dop"},
        {"GPGSA,A,3,04,05", "too few fields"},
        {"GPZDA,201530.00,04,07,1980,00,00", "date out of range"},
        {"GPZDA,201530.00,31,02,2024,00,00", "bad date"},
        {"GPZDA,201530.00,04,07,02,00,00", "bad date"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        rig *r = rig_new(NULL);
        feed(r, sentence(cases[k].body), T0);
        gps_protocol.finish(&r->g, &r->ctx, T0 + 1);
        if (count(r, cases[k].reason) != 1 || r->ctx.reasons.total != 1 || r->n != 0)
            fprintf(stderr, "case %zu (%s): %s\n", k, cases[k].body, r->ctx.last_error);
        CHECK(count(r, cases[k].reason) == 1 && r->ctx.reasons.total == 1);
        CHECK(r->n == 0 && r->ctx.frames_decoded == 0);
        free(r);
    }
    /* the year limit is a setting, both ways */
    rig *r = rig_new((const char *const[]){"--min-year", "1980", NULL});
    feed(r, sentence("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230380,003.1,W"), T0);
    CHECK(r->ctx.reasons.total == 0);
    free(r);
    r = rig_new((const char *const[]){"--min-year", "2000", NULL});
    feed(r, sentence("GPRMC,123519,A,4807.038,N,01131.000,E,022.4,084.4,230399,003.1,W"), T0);
    CHECK(count(r, "date out of range") == 1);
    free(r);
}

static void test_stream_errors_counted(void)
{
    rig *r = rig_new(NULL);
    char stream[4096];
    const char *good = sentence("GPGGA,000001,0100.000,N,00100.000,E,1,05,1.0,0.0,M,,M,,");
    char endless[NMEA_MAX_SENTENCE + 100]; /* longer than any sentence may be */
    endless[0] = '$';
    memset(endless + 1, 'G', sizeof endless - 2);
    endless[sizeof endless - 1] = '\0';
    snprintf(stream, sizeof stream,
             "\x01\x02junk%s"                                           /* garbage, then a good one */
             "$GPGGA,000002,0100.000,N,00100.000,E,1,05,1.0,0.0,M,,M,,*00\r\n" /* bad checksum */
             "$GPRMC,000003,A,0100.000,N,00100.000,E,0.5,90.0,010125,,\r\n"    /* RMC: no checksum */
             "$GPGGA,000004,0100.0"                                      /* cut by the next */
             "%s\r\n"                                                    /* an endless line */
             "$GPGGA,00\x80" "0005*11\r\n",                              /* a byte outside ASCII */
             good, endless);
    feed(r, stream, T0);
    CHECK(count(r, "garbage") == 1);
    CHECK(count(r, "bad checksum") == 1);
    CHECK(count(r, "no checksum") == 1);
    CHECK(count(r, "truncated sentence") == 1);
    CHECK(count(r, "line too long") == 1);
    CHECK(count(r, "bad character") == 1);
    CHECK(r->ctx.frames_decoded == 1);
    /* the stream still works, and a lost port forgets its half sentence */
    feed(r, "$GPGGA,000006,0100.0", T0 + 1000000);
    gps_protocol.reset(&r->g, &r->ctx);
    feed(r, good, T0 + 2000000);
    CHECK(count(r, "truncated sentence") == 1);
    CHECK(r->ctx.frames_decoded == 2);
    free(r);
}

/* Receivers as gpsd's recordings show them (our own sentences in their
 * shapes): each is valid NMEA, and none may be refused or counted. */
static void test_real_receivers(void)
{
    /* HP 58534A: no checksums at all (NMEA makes it optional but in RMC);
     * ZDA's local zone "+00"; DOP and altitude with leading zeros */
    rig *r = rig_new(NULL);
    feed(r, "$GPZDA,222449,25,10,2010,+00,00\r\n", T0);
    feed(r, "$GPGGA,222449,3349.0337,S,01843.9282,E,1,07,02.31,000115.4,M,0033.3,M,,\r\n", T0 + 10000);
    feed(r, "$GPVTG,318.0,T,341.9,M,000.0,N,0000.1,K,A\r\n", T0 + 20000);
    feed(r, "$PFEC,GPtps,101025222449,3,1,1,090101000000,00,15,101025162124,1607,167104\r\n", T0 + 30000);
    gps_protocol.tick(&r->g, &r->ctx, T0 + 700000); /* GGA alone: the epoch times out */
    CHECK(r->n == 1 && r->ctx.reasons.total == 0 && r->ctx.frames_decoded == 4);
    CHECK_NEAR(r->fix[0].latitude_deg, -(33 + 49.0337 / 60), 1e-12);
    CHECK_NEAR(r->fix[0].hdop, 2.31, 1e-12);
    CHECK_NEAR(r->fix[0].altitude_m, 115.4, 1e-9);
    CHECK(r->fix[0].utc_utime == (nmea_unix_day(2010, 10, 25) * 86400 + 22 * 3600 + 24 * 60 + 49) * INT64_C(1000000));
    /* but an RMC without its checksum is refused: there it is mandatory */
    feed(r, "$GPRMC,222450,A,3349.0337,S,01843.9282,E,0.0,318.0,251010,,\r\n", T0 + 1000000);
    CHECK(count(r, "no checksum") == 1);
    /* and a receiver that has checksummed is held to it: a line without is one
     * that lost its *hh */
    feed(r, sentence("GPZDA,222451,25,10,2010,00,00"), T0 + 1100000);
    feed(r, "$GPGGA,222451,3349.0337,S,01843.9282,E,1,07,02.31,000115.4,M,0033.3,M,,\r\n", T0 + 1200000);
    CHECK(count(r, "no checksum") == 2 && r->ctx.frames_decoded == 5);
    feed(r, "$POLYN,TIME,RESTART_OCCURRED\r\n", T0 + 1300000); /* MTK's own, never checksummed */
    CHECK(count(r, "no checksum") == 2 && r->ctx.frames_decoded == 6);
    free(r);

    /* a receiver whose buffer overflowed: sentences run together without CR LF */
    r = rig_new(NULL);
    char run[400];
    const char *a = sentence("GNRMC,101010.00,A,4404.14083,N,12118.85886,W,0.011,,240118,,,A,V");
    const char *b = sentence("GNGGA,101010.00,4404.14083,N,12118.85886,W,1,12,0.68,1142.7,M,-21.3,M,,");
    snprintf(run, sizeof run, "%.*s%s", (int)strlen(a) - 2, a, b);
    feed(r, run, T0);
    CHECK(r->n == 1 && r->ctx.reasons.total == 0);
    CHECK_NEAR(r->fix[0].longitude_deg, -(121 + 18.85886 / 60), 1e-12);
    free(r);

    /* UBX binary frames between the sentences ('$' bytes in them): one run of
     * garbage between two sentences is one count, and no bad character */
    r = rig_new(NULL);
    feed(r, a, T0);
    const char ubx[] = "\xb5\x62\x01\x07\x5c\x00$\x01\x02$G\x00\xff\xb5\x62\x01\x35$\x80";
    gps_protocol.feed(&r->g, &r->ctx, (const uint8_t *)ubx, sizeof ubx - 1, T0 + 1000);
    feed(r, b, T0 + 2000);
    CHECK(r->n == 1 && count(r, "garbage") == 1 && r->ctx.reasons.total == 1);
    free(r);

    /* NMEA 4.11: RMC's nav status (u-blox always V: "not given"), GSA's system
     * id, GSV/GST/TXT/GLL/GNS/DTM and u-blox's PUBX interleaved; an RMC mode
     * 'V' (Magellan's "not valid") with status V is no fix, not a refusal */
    r = rig_new(NULL);
    const char *lines[] = {
        "GNTXT,01,01,02,u-blox AG - www.u-blox.com",
        "GNRMC,083559.00,A,4717.11437,N,00833.91522,E,0.004,77.52,091202,,,A,V",
        "GNGGA,083559.00,4717.11437,N,00833.91522,E,1,08,1.01,499.6,M,48.0,M,,",
        "GNGSA,A,3,23,29,07,08,09,18,26,,,,,,1.94,1.18,1.54,1",
        "GNGSA,A,3,65,67,80,81,82,88,66,,,,,,1.94,1.18,1.54,2",
        "GPGSV,3,1,10,23,38,230,44,29,71,156,47,07,29,116,41,08,09,081,36,1",
        "GNGST,083559.00,1.5,,,,1.2,0.9,2.1",
        "GNGLL,4717.11437,N,00833.91522,E,083559.00,A,A",
        "GNGNS,083559.00,4717.11437,N,00833.91522,E,AANN,08,1.01,499.6,48.0,,,V",
        "GNVTG,77.52,T,,M,0.004,N,0.008,K,A",
        "GPDTM,W84,,0.0,N,0.0,E,0.0,W84",
        "PUBX,00,083559.00,4717.11437,N,00833.91522,E,546.589,G3,2.1,2.0,0.007,77.52,0.007,,0.92,1.19,0.77,9,0,0",
        "INRMC,194101,A,4426.1130,N,07140.5596,W,5.2,77.3,160906,15.8,W",
        "QZGSV,1,1,01,193,60,120,40",
        "GPRMC,205150.00,V,,,,,,,,,,,V",
    };
    for (size_t k = 0; k < sizeof lines / sizeof lines[0]; k++)
        feed(r, sentence(lines[k]), T0 + (int64_t)k * 10000);
    gps_protocol.finish(&r->g, &r->ctx, T0 + 1000000);
    if (r->ctx.reasons.total)
        fprintf(stderr, "real receivers: %s\n", r->ctx.last_error);
    CHECK(r->ctx.reasons.total == 0);
    CHECK(r->ctx.frames_decoded == (int64_t)(sizeof lines / sizeof lines[0]));
    CHECK(r->n == 2); /* the u-blox epoch, and the Humminbird's relayed (IN) RMC */
    CHECK(r->fix[0].quality == 1 && r->fix[0].satellites == 8 && r->fix[0].fix_type == AUV_GPS_FIX_T_FIX_3D);
    CHECK_NEAR(r->fix[1].latitude_deg, 44 + 26.1130 / 60, 1e-12);
    CHECK_NEAR(r->fix[1].speed_mps, 5.2 * 1852.0 / 3600.0, 1e-12);
    free(r);

    /* VTG before NMEA 2.0: four fields, no unit letters; GSA cut short
     * without a fix (iTrek); an unknown mode letter keeps status A's fix */
    r = rig_new(NULL);
    feed(r, sentence("GPGSA,A,1,,,,"), T0);
    feed(r, sentence("GPVTG,054.7,034.4,005.5,010.2"), T0 + 10000);
    feed(r, sentence("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"), T0 + 20000);
    gps_protocol.tick(&r->g, &r->ctx, T0 + 700000);
    CHECK(r->n == 1 && r->ctx.reasons.total == 0);
    CHECK_NEAR(r->fix[0].speed_mps, 5.5 * 1852.0 / 3600.0, 1e-12);
    CHECK_NEAR(r->fix[0].course_deg, 54.7, 1e-12);
    CHECK(isnan(r->fix[0].pdop));
    feed(r, sentence("GPRMC,123520,A,4807.038,N,01131.000,E,022.4,084.4,230324,003.1,W,X"), T0 + 1000000);
    gps_protocol.finish(&r->g, &r->ctx, T0 + 2000000);
    CHECK(r->n == 2 && r->fix[1].quality == 1 && r->ctx.reasons.total == 0);
    free(r);

    /* no fix, as receivers say it: MTK's placeholder 8960.000000 N (89 deg 60
     * min) and 1980's date, TN200's 36000.0000 N, a Garmin's simulator (GGA
     * quality 8, RMC status V mode S), a Hemisphere coasting on no satellite
     * (quality 1, 00 satellites). Valid sentences, nothing refused, no fix;
     * only a sane date is kept (the ZDA-less receiver's UTC) */
    r = rig_new(NULL);
    const char *nofix[] = {
        "GPGGA,235946.005,8960.000000,N,00000.000000,E,0,0,,137.000,M,13.000,M,,",
        "GPRMC,235946.005,V,8960.000000,N,00000.000000,E,0.000,0.00,050180,,,N",
        "GPRMC,000416.984,V,36000.0000,N,72000.0000,E,0.000000,,260120,,",
        "GPRMC,125106,V,3854.5087,N,07726.4523,W,0.0,0.0,241011,10.5,W,S",
        "GPGGA,125106,3854.5087,N,07726.4523,W,8,10,2.0,268.8,M,-33.9,M,,",
        "GPGGA,194050.00,4221.8237733,N,07101.9411707,W,1,00,3.3,10.835,M,-33.320,M,,",
        "GPRMC,194050.00,A,4221.8237733,N,07101.9411707,W,0.0,0.0,070918,,,S",
    };
    for (size_t k = 0; k < sizeof nofix / sizeof nofix[0]; k++)
        feed(r, sentence(nofix[k]), T0 + (int64_t)k * 100000);
    gps_protocol.finish(&r->g, &r->ctx, T0 + 2000000);
    if (r->ctx.reasons.total)
        fprintf(stderr, "no fix: %s\n", r->ctx.last_error);
    CHECK(r->n == 0 && r->ctx.reasons.total == 0);
    CHECK(r->g.have_date && r->g.date_day == nmea_unix_day(2018, 9, 7)); /* the newest sane date, never 1980 */
    free(r);

    /* 9600 baud: GGA, then a dozen GSV over 0.8 s, then the RMC. The line is
     * never quiet, so the epoch waits for its RMC (its speed is the fix's) */
    r = rig_new(NULL);
    feed(r, sentence("GPGGA,053232.438,3114.8789,N,12135.2442,E,1,06,1.2,153.8,M,8.3,M,,0000"), T0);
    for (int k = 1; k <= 12; k++)
        feed(r, sentence("GPGSV,6,1,21,05,00,000,27,06,00,000,24,07,00,000,24,11,00,000,22"), T0 + k * 65000);
    feed(r, sentence("GNRMC,053232.438,A,3114.8789,N,12135.2442,E,0.26,167.42,020315,,,A"), T0 + 850000);
    CHECK(r->n == 1 && r->ctx.reasons.total == 0);
    CHECK_NEAR(r->fix[0].speed_mps, 0.26 * 1852.0 / 3600.0, 1e-12);
    CHECK(r->fix[0].utime == T0);
    free(r);
}

static void test_epochs(void)
{
    rig *r = rig_new(NULL);
    /* sentences split across reads anywhere; RMC before GGA; GSA after */
    const char *rmc = sentence("GNRMC,235959.00,A,0100.000,N,00100.000,E,0.5,90.0,311224,,,D");
    const char *gga = sentence("GNGGA,235959.00,0100.000,N,00100.000,E,2,09,1.2,1.0,M,,M,,");
    const char *gsa = sentence("GNGSA,A,2,01,02,03,,,,,,,,,,3.0,1.2,2.7");
    char all[600];
    snprintf(all, sizeof all, "%s%s%s", rmc, gga, gsa);
    for (size_t i = 0; all[i]; i += 7) {
        char part[8] = {0};
        memcpy(part, all + i, strnlen(all + i, 7));
        feed(r, part, T0 + (int64_t)i * 1000);
    }
    CHECK(r->n == 1);
    CHECK(r->fix[0].utime < T0 + (int64_t)strlen(rmc) * 1000); /* the RMC's receive time */
    CHECK(r->fix[0].quality == 2 && isnan(r->fix[0].pdop));    /* GSA came after: not this epoch's */
    CHECK(r->fix[0].utc_utime == (nmea_unix_day(2024, 12, 31) * 86400 + 86399) * INT64_C(1000000));
    /* the next epoch, past midnight: the date rolls over with the time of day;
     * the GSA of the previous epoch lends its DOPs and its 2D mode */
    feed(r, sentence("GNGGA,000000.00,0100.000,N,00100.000,E,2,09,1.2,1.0,M,,M,,"), T0 + 1000000);
    CHECK(r->n == 1); /* this receiver sends RMC too */
    feed(r, sentence("GNRMC,000000.00,A,0100.000,N,00100.000,E,0.5,90.0,010125,,,D"), T0 + 1010000);
    CHECK(r->n == 2);
    CHECK(r->fix[1].utc_utime == nmea_unix_day(2025, 1, 1) * 86400 * INT64_C(1000000));
    CHECK_NEAR(r->fix[1].pdop, 3.0, 1e-12);
    CHECK(r->fix[1].fix_type == AUV_GPS_FIX_T_FIX_2D);
    /* an epoch that loses its RMC to a bad checksum is published on the timeout */
    feed(r, sentence("GNGGA,000001.00,0100.000,N,00100.000,E,2,09,1.2,1.0,M,,M,,"), T0 + 2000000);
    CHECK(r->n == 2);
    gps_protocol.tick(&r->g, &r->ctx, T0 + 2400000);
    CHECK(r->n == 2);
    gps_protocol.tick(&r->g, &r->ctx, T0 + 2600000);
    CHECK(r->n == 3 && r->fix[2].utime == T0 + 2000000);
    /* its late RMC is not a second fix of the same epoch */
    feed(r, sentence("GNRMC,000001.00,A,0100.000,N,00100.000,E,0.5,90.0,010125,,,D"), T0 + 2700000);
    gps_protocol.finish(&r->g, &r->ctx, T0 + 3000000);
    CHECK(r->n == 3);
    /* no fix: nothing published, nothing refused */
    rig *q = rig_new(NULL);
    feed(q, sentence("GPGGA,000002.00,,,,,0,00,99.99,,,,,,"), T0);
    feed(q, sentence("GPRMC,000002.00,V,,,,,,,010125,,,N"), T0 + 1000);
    feed(q, sentence("GPGGA,,,,,,0,00,99.99,,,,,,"), T0 + 2000);
    gps_protocol.finish(&q->g, &q->ctx, T0 + 1000000);
    CHECK(q->n == 0 && q->ctx.reasons.total == 0 && q->ctx.frames_decoded == 3);
    free(q);
    free(r);
}

static void test_origin_matches_the_simulator(void)
{
    /* python/sim/geo.py at 45 N: radii from WGS-84; 0.01 degree of latitude
     * is 1111.318 m, 0.01 of longitude 788.468 m (its numbers, printed once) */
    rig *r = rig_new((const char *const[]){"--origin", "45.0,-70.0", NULL});
    double n, e;
    gps_to_ned(&r->g, 45.01, -69.99, &n, &e);
    CHECK_NEAR(n, 1111.3177741415357, 1e-6);
    CHECK_NEAR(e, 788.4683509401842, 1e-6);
    char err[200];
    CHECK(gps_set_origin(&r->g, "95,0", err, sizeof err) < 0);
    CHECK(gps_set_origin(&r->g, "45", err, sizeof err) < 0);
    CHECK(gps_set_min_year(&r->g, "1970", err, sizeof err) < 0);
    CHECK(gps_set_uere(&r->g, "-1", err, sizeof err) < 0);
    free(r);
}

/* tests/drivers/corpus/gps/NAME.nmea: hostile streams; a first line
 * "# expect: fixes=N reason=count ..." says what each must give. */
static void test_hostile_corpus(void)
{
    /* run from the checkout's root (tests/drivers/test_drivers_c.py does) */
    const char *dir = "tests/drivers/corpus/gps";
    DIR *d = opendir(dir);
    CHECK(d != NULL);
    if (!d)
        return;
    int files = 0;
    struct dirent *ent;
    while ((ent = readdir(d))) {
        if (!strstr(ent->d_name, ".nmea"))
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
        FILE *f = fopen(path, "rb");
        CHECK(f != NULL);
        if (!f)
            continue;
        static char data[1 << 20];
        size_t n = fread(data, 1, sizeof data - 1, f);
        fclose(f);
        data[n] = '\0';
        char expect[512] = "";
        if (!strncmp(data, "# expect:", 9)) {
            size_t l = strcspn(data, "\n");
            snprintf(expect, sizeof expect, "%.*s", (int)(l - 9), data + 9);
        }
        CHECK(expect[0] != '\0');
        rig *r = rig_new((const char *const[]){"--origin", "0,0", NULL});
        /* in reads of 13 bytes, 10 ms apart (a 9600 baud line) */
        int64_t t = T0;
        for (size_t i = 0; i < n; i += 13, t += 10000) {
            gps_protocol.tick(&r->g, &r->ctx, t);
            gps_protocol.feed(&r->g, &r->ctx, (const uint8_t *)data + i, n - i < 13 ? n - i : 13, t);
        }
        gps_protocol.finish(&r->g, &r->ctx, t);
        for (char *tok = strtok(expect, " "); tok; tok = strtok(NULL, " ")) {
            char *eq = strrchr(tok, '=');
            CHECK(eq != NULL);
            if (!eq)
                continue;
            *eq = '\0';
            for (char *c = tok; *c; c++)
                if (*c == '_')
                    *c = ' ';
            long want = strtol(eq + 1, NULL, 10);
            long got = !strcmp(tok, "fixes") ? r->n : !strcmp(tok, "total") ? (long)r->ctx.reasons.total
                                                                             : (long)count(r, tok);
            if (got != want)
                fprintf(stderr, "%s: %s: want %ld, got %ld (last error: %s)\n", ent->d_name, tok, want, got,
                        r->ctx.last_error);
            CHECK(got == want);
        }
        for (int i = 0; i < r->n; i++)
            CHECK(fabs(r->fix[i].latitude_deg) <= 90 && r->fix[i].quality > 0);
        free(r);
        files++;
    }
    closedir(d);
    CHECK(files >= 5);
}

static const unit_test tests[] = {
    {"gps_published_examples", test_published_examples},
    {"gps_each_talker", test_each_talker},
    {"gps_real_receivers", test_real_receivers},
    {"gps_absurd_values_refused", test_absurd_values_refused},
    {"gps_stream_errors_counted", test_stream_errors_counted},
    {"gps_epochs", test_epochs},
    {"gps_origin_matches_the_simulator", test_origin_matches_the_simulator},
    {"gps_hostile_corpus", test_hostile_corpus},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
