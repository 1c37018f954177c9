/* Unit tests of the PD0 framer, decoder and dvl_t conversion (c/drivers/dvl):
 * ensembles built here byte by byte at the published positions, in every
 * frame, and every way a stream can be wrong. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "auv/auv_dvl_t.h"
#include "drivers/dvl/pd0.h"
#include "../harness/unit.h"

#define DEG (M_PI / 180.0)
#define NCELLS 3

typedef struct {
    int frame;             /* pd0_frame */
    uint8_t ex_extra;      /* tilts, 3-beam, bin mapping bits */
    int facing_up, concave;
    uint8_t angle_code;    /* 0 15, 1 20, 2 30, 3 other (then angle_byte) */
    uint8_t angle_byte;
    int cells, beams;
    uint32_t number;
    double heading, pitch, roll; /* degrees, as written */
    int16_t bt[4];         /* raw mm/s */
    uint32_t range_cm[4];  /* 24 bits */
    int16_t cell[4];       /* every cell */
    int with_bt, with_fixed, with_variable, short_variable;
} spec;

static spec base(void)
{
    spec s;
    memset(&s, 0, sizeof s);
    s.frame = PD0_FRAME_INSTRUMENT;
    s.ex_extra = 0x07;
    s.angle_code = 2;
    s.cells = NCELLS;
    s.beams = 4;
    s.number = 7;
    s.with_bt = s.with_fixed = s.with_variable = 1;
    for (int b = 0; b < 4; b++) {
        s.range_cm[b] = 2000;
        s.bt[b] = PD0_INVALID_VELOCITY;
        s.cell[b] = PD0_INVALID_VELOCITY;
    }
    return s;
}

static void put16(uint8_t *p, unsigned v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

/* Writes the ensemble of s into out; returns its length with the checksum. */
static size_t build(const spec *s, uint8_t *out)
{
    uint8_t types[8][1200];
    size_t lens[8], n = 0;
    if (s->with_fixed) {
        uint8_t *f = types[n];
        memset(f, 0, 59);
        put16(f, 0x0000);
        f[2] = 51;
        f[3] = 41;
        f[4] = (uint8_t)(0x03 | (s->concave ? 0 : 0x08) | (s->facing_up ? 0x80 : 0));
        f[5] = (uint8_t)(0x40 | s->angle_code);
        f[8] = (uint8_t)s->beams;
        f[9] = (uint8_t)s->cells;
        put16(f + 10, 1);
        put16(f + 12, 100);
        put16(f + 14, 50);
        f[25] = (uint8_t)(s->frame << 3 | s->ex_extra);
        f[30] = 0x7D;
        put16(f + 32, 100);
        f[54] = 0x78; /* serial number 0x12345678 */
        f[55] = 0x56;
        f[56] = 0x34;
        f[57] = 0x12;
        f[58] = s->angle_byte;
        lens[n++] = 59;
    }
    if (s->with_variable) {
        uint8_t *v = types[n];
        memset(v, 0, 65);
        put16(v, 0x0080);
        put16(v + 2, s->number & 0xFFFF);
        v[4] = 26; /* old clock: 26-03-14 12:34:56.78 */
        v[5] = 3;
        v[6] = 14;
        v[7] = 12;
        v[8] = 34;
        v[9] = 56;
        v[10] = 78;
        v[11] = (uint8_t)(s->number >> 16);
        put16(v + 14, 1500);
        put16(v + 16, 123);
        put16(v + 18, (unsigned)lround(s->heading * 100));
        put16(v + 20, (unsigned)(uint16_t)(int16_t)lround(s->pitch * 100));
        put16(v + 22, (unsigned)(uint16_t)(int16_t)lround(s->roll * 100));
        put16(v + 24, 35);
        put16(v + 26, (unsigned)(uint16_t)(int16_t)-150);
        v[57] = 20; /* Y2K clock: 2026-03-14 12:34:57.00 */
        v[58] = 26;
        v[59] = 3;
        v[60] = 14;
        v[61] = 12;
        v[62] = 34;
        v[63] = 57;
        v[64] = 0;
        lens[n++] = s->short_variable ? 42 : 65;
    }
    uint8_t *vel = types[n];
    put16(vel, 0x0100);
    for (int c = 0; c < s->cells; c++)
        for (int b = 0; b < s->beams; b++)
            put16(vel + 2 + 2 * (c * s->beams + b), (unsigned)(uint16_t)s->cell[b]);
    lens[n++] = 2 + 2 * (size_t)s->cells * (size_t)s->beams;
    for (unsigned id = 0x0200; id <= 0x0400; id += 0x0100) {
        uint8_t *t = types[n];
        put16(t, id);
        memset(t + 2, 100, (size_t)s->cells * (size_t)s->beams);
        lens[n++] = 2 + (size_t)s->cells * (size_t)s->beams;
    }
    if (s->with_bt) {
        uint8_t *t = types[n];
        memset(t, 0, 85);
        put16(t, 0x0600);
        put16(t + 2, 1);
        for (int b = 0; b < 4; b++) {
            put16(t + 16 + 2 * b, s->range_cm[b] & 0xFFFF);
            put16(t + 24 + 2 * b, (unsigned)(uint16_t)s->bt[b]);
            t[32 + b] = 250;
            t[40 + b] = 100;
            t[77 + b] = (uint8_t)(s->range_cm[b] >> 16);
        }
        lens[n++] = 85;
    }
    size_t at = 6 + 2 * n;
    out[0] = out[1] = 0x7F;
    out[4] = 0;
    out[5] = (uint8_t)n;
    for (size_t i = 0; i < n; i++) {
        put16(out + 6 + 2 * i, (unsigned)at);
        memcpy(out + at, types[i], lens[i]);
        at += lens[i];
    }
    put16(out + 2, (unsigned)at);
    put16(out + at, pd0_checksum(out, at));
    return at + 2;
}

/* Recomputes the checksum after a test edited the bytes. */
static void reseal(uint8_t *p)
{
    size_t n = (size_t)p[2] | (size_t)p[3] << 8;
    put16(p + n, pd0_checksum(p, n));
}

static pd0_ensemble E; /* large: not on the stack */
static uint8_t B[8192];

static void test_decode_fields(void)
{
    spec s = base();
    s.heading = 123.45;
    s.pitch = -4.5;
    s.roll = 2.25;
    s.number = 0x012345;
    s.range_cm[2] = 0x01ABCD; /* with its MSB byte: 1096.13 m */
    s.range_cm[3] = 0;        /* no bottom in beam 4 */
    s.bt[0] = 100;
    s.bt[1] = -200;
    s.bt[2] = 300;
    s.bt[3] = PD0_INVALID_VELOCITY;
    s.cell[0] = 10;
    size_t n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK(E.ensemble_number == 0x012345);
    CHECK(E.n_beams == 4 && E.n_cells == NCELLS);
    CHECK_NEAR(E.beam_angle_deg, 30.0, 0);
    CHECK(E.convex == 1 && E.facing_up == 0);
    CHECK(E.frequency_khz == 600);
    CHECK(E.frame == PD0_FRAME_INSTRUMENT && E.tilts_used && E.three_beam && E.bin_mapping);
    CHECK_NEAR(E.cell_size_m, 1.0, 1e-12);
    CHECK_NEAR(E.blank_m, 0.5, 1e-12);
    CHECK_NEAR(E.bin1_distance_m, 1.0, 1e-12);
    CHECK(E.serial_number == 0x12345678);
    CHECK_NEAR(E.heading_deg, 123.45, 1e-9);
    CHECK_NEAR(E.pitch_deg, -4.5, 1e-9);
    CHECK_NEAR(E.roll_deg, 2.25, 1e-9);
    CHECK_NEAR(E.depth_m, 12.3, 1e-9);
    CHECK_NEAR(E.temperature_c, -1.5, 1e-9);
    CHECK_NEAR(E.salinity_ppt, 35, 0);
    CHECK_NEAR(E.sound_speed_mps, 1500, 0);
    /* the Y2K clock wins over the old one */
    CHECK(E.rtc.valid && E.rtc.y2k && E.rtc.year == 2026 && E.rtc.second == 57 && E.rtc.hundredths == 0);
    CHECK(pd0_rtc_utime(&E.rtc) == 1773491697LL * 1000000);
    CHECK(E.has_velocity && E.has_correlation && E.has_intensity && E.has_percent_good && E.has_bottom_track);
    CHECK_NEAR(E.velocity_mps[2][0], 0.010, 1e-12);
    CHECK(isnan(E.velocity_mps[2][1]));
    CHECK_NEAR(E.bt_range_m[0], 20.0, 1e-12);
    CHECK_NEAR(E.bt_range_m[2], 0x01ABCD * 0.01, 1e-9);
    CHECK_NEAR(E.bt_range_m[3], -1.0, 0);
    CHECK_NEAR(E.bt_velocity_mps[1], -0.2, 1e-12);
    CHECK(isnan(E.bt_velocity_mps[3]));
    CHECK(E.bt_correlation[0] == 250 && E.bt_percent_good[3] == 100);
    /* an old, short variable leader: the 2-digit clock, this century */
    s.short_variable = 1;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK(E.rtc.valid && !E.rtc.y2k && E.rtc.year == 2026 && E.rtc.second == 56 && E.rtc.hundredths == 78);
    /* a month 13 is not a time: the ensemble stays, its clock is not valid */
    s.short_variable = 0;
    n = build(&s, B);
    B[6 + 2 * 7 + 59 + 59] = 13;
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK(!E.rtc.valid && pd0_rtc_utime(&E.rtc) == 0);
}

/* Each frame's bottom-track values for a vehicle going 1 m/s forward, 0.5
 * starboard, 0.2 down, and the body velocity it must come back as. */
static void expect_body(const spec *s, double vx, double vy, double vz, double tol)
{
    size_t n = build(s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_mounting m;
    pd0_mounting_default(&m);
    auv_dvl_t d;
    memset(&d, 0, sizeof d);
    pd0_to_dvl(&E, &m, &d);
    CHECK(d.mode == AUV_DVL_T_MODE_BOTTOM_LOCK);
    CHECK_NEAR(d.velocity_mps[0], vx, tol);
    CHECK_NEAR(d.velocity_mps[1], vy, tol);
    CHECK_NEAR(d.velocity_mps[2], vz, tol);
}

static void test_frames(void)
{
    /* instrument = ship axes when down and aligned: X stbd, Y fwd, Z up; the
     * bottom moves opposite to the vehicle */
    spec s = base();
    s.bt[0] = -500;
    s.bt[1] = -1000;
    s.bt[2] = 200;
    s.bt[3] = 0;
    expect_body(&s, 1.0, 0.5, 0.2, 1e-9);
    s.frame = PD0_FRAME_SHIP;
    s.ex_extra = 0; /* no tilts: as given */
    s.pitch = 10;
    expect_body(&s, 1.0, 0.5, 0.2, 1e-9);
    /* facing up: X and Z negated */
    s = base();
    s.facing_up = 1;
    s.bt[0] = 500;
    s.bt[1] = -1000;
    s.bt[2] = -200;
    expect_body(&s, 1.0, 0.5, 0.2, 1e-9);
    /* earth, level, heading 90: forward is east, starboard is south, down is down */
    s = base();
    s.frame = PD0_FRAME_EARTH;
    s.heading = 90;
    s.bt[0] = -1000; /* E of the bottom: -(east of the vehicle) */
    s.bt[1] = 500;   /* N: the vehicle goes 0.5 south */
    s.bt[2] = 200;   /* U: the vehicle goes down */
    expect_body(&s, 1.0, 0.5, 0.2, 1e-9);
    /* earth with tilts: pitch 10 up, heading 0, forward only: the bottom is
     * seen moving south and up (the vehicle climbs); pitch from the internal
     * sensor is the tilt atan(tan p / cos r) (roll 0: the same) */
    s.heading = 0;
    s.pitch = 10;
    s.bt[0] = 0;
    s.bt[1] = (int16_t)lround(-1000 * cos(10 * DEG));
    s.bt[2] = (int16_t)lround(-1000 * sin(10 * DEG));
    expect_body(&s, 1.0, 0.0, 0.0, 2e-3);
    /* beam: 4 beams at 30 degrees, convex; forward 1 m/s: beam 3 (forward)
     * closes on the seabed (positive: toward the transducer), beam 4 opens */
    s = base();
    s.frame = PD0_FRAME_BEAM;
    double sn = sin(30 * DEG);
    s.bt[0] = 0;
    s.bt[1] = 0;
    s.bt[2] = (int16_t)lround(1000 * sn);
    s.bt[3] = (int16_t)lround(-1000 * sn);
    expect_body(&s, 1.0, 0.0, 0.0, 1e-9);
    /* 3-beam: beam 2 lost, solved with zero error velocity */
    s.bt[1] = PD0_INVALID_VELOCITY;
    expect_body(&s, 1.0, 0.0, 0.0, 1e-9);
    /* not allowed: no velocity */
    s.ex_extra = 0;
    size_t n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_mounting m;
    pd0_mounting_default(&m);
    auv_dvl_t d;
    memset(&d, 0, sizeof d);
    pd0_to_dvl(&E, &m, &d);
    CHECK(d.mode == AUV_DVL_T_MODE_NONE && d.velocity_sigma_mps < 0);
    CHECK(d.device_frame == AUV_DVL_T_FRAME_BEAM);
}

static void test_invalid_markers_and_modes(void)
{
    spec s = base();
    /* bottom track invalid, the profile good: water track from the cells */
    s.cell[0] = -300;
    s.cell[1] = -1200;
    s.cell[2] = 0;
    s.cell[3] = 5;
    size_t n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_mounting m;
    pd0_mounting_default(&m);
    auv_dvl_t d;
    memset(&d, 0, sizeof d);
    pd0_to_dvl(&E, &m, &d);
    CHECK(d.mode == AUV_DVL_T_MODE_WATER_TRACK);
    CHECK_NEAR(d.velocity_mps[0], 1.2, 1e-9);
    CHECK_NEAR(d.velocity_mps[1], 0.3, 1e-9);
    CHECK_NEAR(d.error_velocity_mps, 0.005, 1e-9);
    CHECK(d.ensemble == 7 && d.has_environment && d.device_utime > 0);
    /* an invalid Z in every cell: nothing */
    s.cell[2] = PD0_INVALID_VELOCITY;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_to_dvl(&E, &m, &d);
    CHECK(d.mode == AUV_DVL_T_MODE_NONE);
    CHECK(d.velocity_mps[0] == 0 && d.velocity_mps[1] == 0);
    /* level, BT range 20 m (RDI's vertical range): altitude 20 m, slant
     * 20 / cos(30 deg) = 23.09 m; a beam with no bottom is left out; two
     * beams only: no altitude */
    CHECK_NEAR(d.altitude_m, 20.0, 1e-6);
    CHECK_NEAR(d.beam_range_m[0], 20.0 / cos(30 * DEG), 1e-5);
    s.range_cm[0] = 0;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_to_dvl(&E, &m, &d);
    CHECK_NEAR(d.altitude_m, 20.0, 1e-6);
    CHECK(d.beam_range_m[0] < 0);
    s.range_cm[1] = 0;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_to_dvl(&E, &m, &d);
    CHECK(d.altitude_m < 0);
    /* pitched 10 degrees up over a flat seabed 15 m below: each beam's slant
     * range is 15 / its downward component, its BT range that x cos(beam
     * angle) (RDI's vertical range, no pitch in it), and the altitude comes back */
    s = base();
    s.pitch = atan(tan(10 * DEG) / cos(0)) / DEG;
    double th = 30 * DEG, p = 10 * DEG;
    double down3 = cos(th) * cos(p) - sin(th) * sin(p); /* forward beam: nearer the horizon */
    double down4 = cos(th) * cos(p) + sin(th) * sin(p);
    double down12 = cos(th) * cos(p);
    s.range_cm[0] = s.range_cm[1] = (uint32_t)lround(1500 * cos(th) / down12);
    s.range_cm[2] = (uint32_t)lround(1500 * cos(th) / down3);
    s.range_cm[3] = (uint32_t)lround(1500 * cos(th) / down4);
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK_NEAR(pd0_altitude(&E), 15.0, 0.01);
}

static void test_mounting(void)
{
    /* a DVL turned 45 degrees to starboard: its forward is the vehicle's
     * forward-starboard diagonal */
    spec s = base();
    s.bt[0] = 0;
    s.bt[1] = -1000;
    s.bt[2] = 0;
    size_t n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_mounting m;
    pd0_mounting_default(&m);
    m.yaw_rad = 45 * DEG;
    double v[3], err;
    CHECK(pd0_body_velocity(&E, &m, E.bt_velocity_mps, v, &err));
    CHECK_NEAR(v[0], sqrt(0.5), 1e-9);
    CHECK_NEAR(v[1], sqrt(0.5), 1e-9);
    CHECK_NEAR(v[2], 0.0, 1e-9);
}

/* Feeds bytes in pieces of `step` (0: one piece); counts ensembles and refusals. */
static int feed(pd0_framer *f, const uint8_t *p, size_t n, size_t step, int refused[PD0_RESULT_COUNT],
                uint32_t *last_number)
{
    int ok = 0;
    size_t at = 0;
    while (at < n) {
        size_t k = step && step < n - at ? step : n - at;
        const uint8_t *q = p + at, *e;
        size_t left = k, used, len;
        int r;
        while ((r = pd0_framer_push(f, q, left, &used, &e, &len)) != -1) {
            q += used;
            left -= used;
            if (r == PD0_OK) {
                r = pd0_decode(e, len, &E);
                if (r == PD0_OK) {
                    ok++;
                    if (last_number)
                        *last_number = E.ensemble_number;
                    continue;
                }
            }
            refused[r]++;
        }
        CHECK(used == left);
        at += k;
    }
    return ok;
}

static void test_split_at_every_position(void)
{
    spec s = base();
    size_t n1 = build(&s, B);
    s.number = 8;
    size_t n2 = build(&s, B + n1);
    size_t n = n1 + n2;
    for (size_t cut = 0; cut <= n; cut++) {
        pd0_framer f;
        pd0_framer_init(&f);
        int refused[PD0_RESULT_COUNT] = {0};
        uint32_t last = 0;
        int ok = feed(&f, B, cut, 0, refused, &last) + feed(&f, B + cut, n - cut, 0, refused, &last);
        if (ok != 2 || last != 8 || f.garbage_bytes)
            UNIT_FAIL("cut at %zu: %d ensembles, last %u, %llu garbage", cut, ok, last,
                      (unsigned long long)f.garbage_bytes);
        for (int r = 1; r < PD0_RESULT_COUNT; r++)
            CHECK(refused[r] == 0);
    }
    /* and a byte at a time */
    pd0_framer f;
    pd0_framer_init(&f);
    int refused[PD0_RESULT_COUNT] = {0};
    CHECK(feed(&f, B, n, 1, refused, NULL) == 2);
}

static void test_garbage_and_resync(void)
{
    static uint8_t stream[8192];
    spec s = base();
    size_t at = 0;
    const char junk[] = "\x01\x7f\x02garbage\x7f";
    memcpy(stream, junk, sizeof junk - 1);
    at += sizeof junk - 1;
    at += build(&s, stream + at);
    /* a header with a length shorter than itself: refused, the stream goes on */
    const uint8_t absurd[] = {0x7F, 0x7F, 0x05, 0x00, 0x00, 0x05};
    memcpy(stream + at, absurd, sizeof absurd);
    at += sizeof absurd;
    /* a 7F 7F in garbage, its length 64 kB: refused by its offset table at
     * once, not held for the bytes it asks for (the ensembles behind it come
     * out now, ok == 3 below) */
    const uint8_t false_header[] = {0x7F, 0x7F, 0xFF, 0xFF, 0x00, 0x02, 0x34, 0x12, 0x00, 0x10};
    memcpy(stream + at, false_header, sizeof false_header);
    at += sizeof false_header;
    /* an ensemble with a bad sum, then a good one right after */
    size_t bad = build(&s, stream + at);
    stream[at + 40] ^= 0x55;
    at += bad;
    s.number = 8;
    at += build(&s, stream + at);
    /* a device that stopped mid-ensemble and started a new one */
    size_t cut = build(&s, stream + at);
    at += cut / 2;
    s.number = 9;
    at += build(&s, stream + at);
    pd0_framer f;
    pd0_framer_init(&f);
    int refused[PD0_RESULT_COUNT] = {0};
    uint32_t last = 0;
    int ok = feed(&f, stream, at, 7, refused, &last);
    CHECK(ok == 3 && last == 9);
    /* the junk's last 7F with the ensemble's 7F 7F is a header of 7F 15 01 as
     * its 24-bit length; then the short length */
    CHECK(refused[PD0_BAD_LENGTH] == 2);
    CHECK(refused[PD0_BAD_OFFSET] == 1);
    CHECK(refused[PD0_BAD_CHECKSUM] == 2); /* the corrupted one, and the one cut by a new ensemble */
    CHECK(f.garbage_bytes > 0);
    /* a device that stops mid-ensemble for good: a read timeout flushes it */
    feed(&f, stream + sizeof junk - 1, 100, 0, refused, NULL);
    CHECK(pd0_framer_flush(&f) == PD0_TRUNCATED);
    CHECK(pd0_framer_flush(&f) == -1);
}

static void test_every_refusal(void)
{
    spec s = base();
    size_t n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    /* a length pointing past the buffer */
    CHECK(pd0_decode(B, n - 3, &E) == PD0_TRUNCATED);
    put16(B + 2, 60000); /* any 16-bit length is a PD0 length: this one is past the buffer */
    CHECK(pd0_decode(B, n, &E) == PD0_TRUNCATED);
    put16(B + 2, 4);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_LENGTH);
    /* the byte after the length is its MSB (the Pathfinder's manual): over 64 kB */
    n = build(&s, B);
    B[4] = 1;
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_LENGTH);
    n = build(&s, B);
    B[n - 1] ^= 1;
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_CHECKSUM);
    n = build(&s, B);
    B[5] = 0;
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_HEADER);
    /* offsets: inside the header, past the end, out of order, and the first
     * one not right after the offsets */
    n = build(&s, B);
    put16(B + 6, 4);
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_OFFSET);
    n = build(&s, B);
    put16(B + 8, (unsigned)(n - 3));
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_OFFSET);
    n = build(&s, B);
    put16(B + 8, 20);
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_OFFSET);
    n = build(&s, B);
    put16(B + 6, (unsigned)(B[6] | B[7] << 8) + 2);
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_OFFSET);
    /* a velocity type too short for its cells: the cell count raised */
    n = build(&s, B);
    B[20 + 9] = NCELLS + 1;
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_SHORT_TYPE);
    n = build(&s, B);
    B[20 + 9] = 255; /* every cell count of the byte is one (pd0_shapes: 132), here more than the bytes */
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_SHORT_TYPE);
    n = build(&s, B);
    B[20 + 8] = 0;
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_BEAMS);
    n = build(&s, B);
    B[20 + 8] = PD0_MAX_BEAMS + 1;
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_BEAMS);
    s.angle_code = 3;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_BEAM_ANGLE);
    s.angle_byte = 25;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && E.beam_angle_deg == 25);
    s = base();
    s.heading = 360.5;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_ATTITUDE);
    s = base();
    s.with_fixed = 0;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_NO_FIXED_LEADER);
    s = base();
    s.with_variable = 0;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_NO_VARIABLE_LEADER);
    /* the variable leader's ID written over the velocity's */
    s = base();
    n = build(&s, B);
    size_t vel_off = (size_t)B[10] | (size_t)B[11] << 8;
    put16(B + vel_off, 0x0080);
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_DUPLICATE_TYPE);
    /* an unknown data type is skipped and counted */
    n = build(&s, B);
    put16(B + vel_off, 0x2000);
    reseal(B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && E.unknown_types == 1 && !E.has_velocity);
    for (int r = 0; r < PD0_RESULT_COUNT; r++)
        CHECK(strcmp(pd0_result_name((pd0_result)r), "unknown") != 0);
    CHECK_STR(pd0_result_name(PD0_BAD_OFFSET), "offset outside ensemble");
    CHECK_STR(pd0_result_name(PD0_TRUNCATED), "truncated ensemble");
}

static void test_continuity(void)
{
    pd0_continuity c = {0};
    CHECK(pd0_continuity_update(&c, 100, 0) == 0);
    CHECK(pd0_continuity_update(&c, 101, 0) == 0);
    CHECK(pd0_continuity_update(&c, 104, 0) == 2);
    CHECK(pd0_continuity_update(&c, 104, 0) == -1);
    CHECK(pd0_continuity_update(&c, 3, 0) == -2);
    CHECK(c.gaps == 1 && c.missed == 2 && c.repeats == 1 && c.restarts == 1 && c.in_order == 2);
    /* the 16-bit number rolls into its MSB byte, and 24 bits wrap to 0 */
    CHECK(pd0_continuity_update(&c, 0xFFFF, 0) == 0xFFFF - 3 - 1);
    CHECK(pd0_continuity_update(&c, 0x10000, 0) == 0);
    CHECK(pd0_continuity_update(&c, 0xFFFFFE, 0) == -2); /* more than half the range ahead: behind */
    CHECK(pd0_continuity_update(&c, 0xFFFFFF, 0) == 0);
    CHECK(pd0_continuity_update(&c, 0, 0) == 0);
    CHECK(pd0_continuity_update(&c, 2, 0) == 1);
    /* from the bytes: LSB 0xFFFF then MSB 1, LSB 0 */
    spec s = base();
    s.number = 0x00FFFF;
    size_t n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_continuity d = {0};
    pd0_continuity_update(&d, E.ensemble_number, 0);
    s.number = 0x010000;
    n = build(&s, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK(pd0_continuity_update(&d, E.ensemble_number, 0) == 0 && E.ensemble_number == 65536);
}

static const unit_test tests[] = {
    {"pd0_decode_fields", test_decode_fields},
    {"pd0_frames", test_frames},
    {"pd0_invalid_markers_and_modes", test_invalid_markers_and_modes},
    {"pd0_mounting", test_mounting},
    {"pd0_split_at_every_position", test_split_at_every_position},
    {"pd0_garbage_and_resync", test_garbage_and_resync},
    {"pd0_every_refusal", test_every_refusal},
    {"pd0_continuity", test_continuity},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_pd0(void) { unit_register_list(tests); }
