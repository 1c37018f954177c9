/* The PD0 of real instruments, not only our emulator's: ensembles built here
 * in the shapes RDI's units and their PC programs write (c/drivers/dvl,
 * docs/drivers.md "DVL: Teledyne RDI PD0"):
 *   - WinRiver II: 132 cells, 60+ data types (an NMEA sentence each, 0x2022)
 *     and its 0x2101 navigation type;
 *   - a Workhorse with the waves option: 7F 79 waves packets between ensembles;
 *   - an Ocean Surveyor (VMDAS): a 60-byte variable leader without the Y2K
 *     clock, an 81-byte bottom track, fixed attitude types 0x3000 / 0x30D8;
 *   - a Sentinel V: the beam angle in the fixed leader's byte ("other", 25
 *     degrees), its 0x7000.. and beam-5 types; a leader saying 3 or 5 beams
 *     over the same four values a cell;
 *   - an ensemble longer than 16 kB, a bottom-track-only unit (0 cells);
 *   - a count restarted one back at another time (a new ping, not a repeat). */
#include <math.h>
#include <string.h>

#include "auv/auv_dvl_t.h"
#include "drivers/dvl/pd0.h"
#include "../harness/unit.h"

static void put16(uint8_t *p, unsigned v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

/* ------------------------------------------------------------ an assembler */
#define MAX_OUT 70000
static uint8_t types_buf[MAX_OUT];
static size_t type_off[256], type_len[256], ntypes, types_used;

static void begin(void) { ntypes = types_used = 0; }

/* Appends a data type: its ID, then len-2 bytes of body (or zeros). */
static uint8_t *add(unsigned id, size_t len)
{
    uint8_t *t = types_buf + types_used;
    memset(t, 0, len);
    put16(t, id);
    type_off[ntypes] = types_used;
    type_len[ntypes++] = len;
    types_used += len;
    return t;
}

/* Header (7F lead, 7F for an ensemble, 79 for a waves packet), types, sum. */
static size_t finish(uint8_t second, uint8_t *out)
{
    size_t at = 6 + 2 * ntypes;
    out[0] = 0x7F;
    out[1] = second;
    out[4] = 0;
    out[5] = (uint8_t)ntypes;
    for (size_t i = 0; i < ntypes; i++) {
        put16(out + 6 + 2 * i, (unsigned)at);
        memcpy(out + at, types_buf + type_off[i], type_len[i]);
        at += type_len[i];
    }
    put16(out + 2, (unsigned)at);
    put16(out + at, pd0_checksum(out, at));
    return at + 2;
}

typedef struct {
    int cells, beams, fixed_len, variable_len, bt_len;
    uint8_t cfg_lsb, cfg_msb, ex, angle_byte, century, year;
    uint32_t number;
    uint8_t second;
    int16_t vel[4];  /* every cell's values, per beam */
} shape;

static shape workhorse(void)
{
    shape s = {.cells = 10, .beams = 4, .fixed_len = 59, .variable_len = 65, .bt_len = 85};
    s.cfg_lsb = 0x4A; /* 300 kHz, convex, down */
    s.cfg_msb = 0x41; /* 20 degrees, 4-beam Janus */
    s.ex = 3 << 3 | 0x07;
    s.century = 20;
    s.year = 17;
    s.number = 224;
    for (int b = 0; b < 4; b++)
        s.vel[b] = (int16_t)(100 * (b + 1));
    return s;
}

/* The leaders, the profile and the bottom track of shape s (begin() first). */
static void add_standard(const shape *s)
{
    uint8_t *f = add(0x0000, (size_t)s->fixed_len);
    f[2] = 51;
    f[3] = 40;
    f[4] = s->cfg_lsb;
    f[5] = s->cfg_msb;
    f[8] = (uint8_t)s->beams;
    f[9] = (uint8_t)s->cells;
    put16(f + 10, 1);
    put16(f + 12, 25);
    put16(f + 14, 25);
    f[25] = s->ex;
    f[30] = 0x7D;
    put16(f + 32, 50);
    if (s->fixed_len >= 59)
        f[58] = s->angle_byte;
    uint8_t *v = add(0x0080, (size_t)s->variable_len);
    put16(v + 2, s->number & 0xFFFF);
    v[4] = s->year; /* old clock: yy-04-05 08:09:18.72 */
    v[5] = 4;
    v[6] = 5;
    v[7] = 8;
    v[8] = 9;
    v[9] = s->second;
    v[10] = 72;
    v[11] = (uint8_t)(s->number >> 16);
    put16(v + 14, 1415);
    put16(v + 18, 10384); /* heading 103.84 */
    put16(v + 20, (unsigned)(uint16_t)-397);
    put16(v + 22, 73);
    if (s->variable_len >= 65) {
        v[57] = s->century;
        v[58] = s->year;
        v[59] = 4;
        v[60] = 5;
        v[61] = 8;
        v[62] = 9;
        v[63] = s->second;
        v[64] = 72;
    }
    /* four values a cell whatever the leader's beam count (the published
     * "2 bytes + 8 bytes per depth cell") */
    size_t per = (size_t)s->cells * 4;
    uint8_t *vel = add(0x0100, 2 + 2 * per);
    for (int c = 0; c < s->cells; c++)
        for (int b = 0; b < 4; b++)
            put16(vel + 2 + 2 * (c * 4 + b),
                  (unsigned)(uint16_t)(s->vel[b] == PD0_INVALID_VELOCITY ? s->vel[b] : s->vel[b] + c));
    for (unsigned id = 0x0200; id <= 0x0400; id += 0x0100)
        memset(add(id, 2 + per) + 2, 100, per);
    if (s->bt_len) {
        uint8_t *t = add(0x0600, (size_t)s->bt_len);
        put16(t + 2, 1);
        for (int b = 0; b < 4; b++) {
            put16(t + 16 + 2 * b, 1000 + 100 * (unsigned)b); /* 10, 11, 12, 13 m */
            put16(t + 24 + 2 * b, (unsigned)(uint16_t)(-500 + 10 * b));
            t[32 + b] = 250;
            t[40 + b] = 100;
            if (s->bt_len >= 81)
                t[77 + b] = b == 3; /* beam 4: 655.36 m more */
        }
    }
}

/* An NMEA sentence in WinRiver II's 0x2022 type: ID, its own specific ID,
 * the sentence's length, a time, then the sentence. */
static void add_nmea(const char *sentence)
{
    size_t n = strlen(sentence);
    uint8_t *t = add(0x2022, 2 + 2 + 2 + 8 + n);
    put16(t + 2, 104); /* GGA */
    put16(t + 4, (unsigned)n);
    memcpy(t + 14, sentence, n);
}

static pd0_ensemble E;
static uint8_t B[MAX_OUT], S[4 * MAX_OUT];

/* Every byte through the framer in reads of `step` (0: all at once) and each
 * ensemble through the decoder; returns the ensembles decoded. */
static int frame_all(pd0_framer *f, const uint8_t *p, size_t n, size_t step, int refused[PD0_RESULT_COUNT])
{
    int ok = 0;
    for (size_t at = 0; at < n;) {
        size_t k = step && n - at > step ? step : n - at, left = k, used;
        const uint8_t *q = p + at, *ens;
        size_t len;
        int r;
        while ((r = pd0_framer_push(f, q, left, &used, &ens, &len)) != -1) {
            q += used;
            left -= used;
            if (r == PD0_OK && (r = pd0_decode(ens, len, &E)) == PD0_OK)
                ok++;
            else
                refused[r]++;
        }
        at += k;
    }
    return ok;
}

static int no_refusals(const int refused[PD0_RESULT_COUNT])
{
    for (int r = 0; r < PD0_RESULT_COUNT; r++)
        if (refused[r])
            return 0;
    return 1;
}

static void test_winriver_many_types_and_cells(void)
{
    shape s = workhorse();
    s.cells = 132;
    begin();
    add_standard(&s);
    for (int i = 0; i < 60; i++)
        add_nmea("$GPGGA,080918.72,4930.0000,N,12300.0000,W,2,09,0.9,12.0,M,-17.0,M,,*4B\r\n");
    add(0x2101, 84);
    size_t n = finish(0x7F, B);
    CHECK(ntypes == 68 && n > 7000);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK(E.n_cells == 132 && E.n_beams == 4 && E.unknown_types == 61);
    CHECK_NEAR(E.velocity_mps[131][3], (400 + 131) * 1e-3, 1e-12);
    CHECK_NEAR(E.velocity_mps[0][0], 0.1, 1e-12);
    CHECK(E.has_bottom_track && E.frame == PD0_FRAME_EARTH);
    CHECK_NEAR(E.bt_range_m[3], 13.0 + 655.36, 1e-9);
    CHECK_NEAR(E.beam_angle_deg, 20.0, 0);
    auv_dvl_t d;
    memset(&d, 0, sizeof d);
    pd0_mounting m;
    pd0_mounting_default(&m);
    pd0_to_dvl(&E, &m, &d);
    CHECK(d.mode == AUV_DVL_T_MODE_BOTTOM_LOCK && d.ensemble == 224);
    /* two of them through the framer a byte at a time: no refusal */
    memcpy(S, B, n);
    memcpy(S + n, B, n);
    pd0_framer f;
    pd0_framer_init(&f);
    int refused[PD0_RESULT_COUNT] = {0};
    CHECK(frame_all(&f, S, 2 * n, 1, refused) == 2 && no_refusals(refused) && f.garbage_bytes == 0);
}

/* A waves packet: 7F 79, the same header, a sum. */
static size_t waves_packet(uint8_t *out, size_t body)
{
    begin();
    uint8_t *t = add(0x0103, body);
    for (size_t i = 2; i < body; i++)
        t[i] = (uint8_t)(i * 7); /* not zeros: the sum means something */
    add(0x0203, 40);
    return finish(0x79, out);
}

static void test_waves_packets_between_ensembles(void)
{
    shape s = workhorse();
    begin();
    add_standard(&s);
    size_t ens = finish(0x7F, B), at = 0;
    at += waves_packet(S + at, 80);
    memcpy(S + at, B, ens);
    at += ens;
    for (int i = 0; i < 3; i++)
        at += waves_packet(S + at, 70 + (size_t)i);
    memcpy(S + at, B, ens);
    at += ens;
    /* a waves packet with a wrong sum: not a packet, its bytes are garbage,
     * and nothing is refused (it is no ensemble) */
    size_t broken = waves_packet(S + at, 60);
    S[at + 20] ^= 0xFF;
    at += broken;
    memcpy(S + at, B, ens);
    at += ens;
    size_t steps[] = {0, 1, 13};
    for (size_t i = 0; i < sizeof steps / sizeof *steps; i++) {
        pd0_framer f;
        pd0_framer_init(&f);
        int refused[PD0_RESULT_COUNT] = {0};
        CHECK(frame_all(&f, S, at, steps[i], refused) == 3);
        CHECK(no_refusals(refused));
        CHECK(f.waves_packets == 4);
        CHECK(f.garbage_bytes == broken);
        CHECK(pd0_framer_flush(&f) == -1);
    }
    /* a waves packet cut by the end of the stream is garbage, not a cut ensemble */
    pd0_framer f;
    pd0_framer_init(&f);
    int refused[PD0_RESULT_COUNT] = {0};
    size_t n = waves_packet(S, 80);
    CHECK(frame_all(&f, S, n - 10, 0, refused) == 0 && no_refusals(refused));
    CHECK(pd0_framer_flush(&f) == -1 && f.garbage_bytes == n - 10);
}

static void test_ocean_surveyor_leaders(void)
{
    shape s = workhorse();
    s.fixed_len = 60;
    s.variable_len = 60; /* no Y2K clock */
    s.bt_len = 81;       /* its range MSBs are the last four bytes */
    s.cfg_lsb = 0x48;    /* 75 kHz, convex, down */
    s.cfg_msb = 0x02;    /* 30 degrees */
    s.ex = 0;            /* beam coordinates */
    s.cells = 80;
    s.year = 22;
    begin();
    add_standard(&s);
    add(0x3000, 34);
    add(0x30D8, 52);
    size_t n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK(E.unknown_types == 2 && E.n_cells == 80 && E.frequency_khz == 75 && E.frame == PD0_FRAME_BEAM);
    CHECK(E.rtc.valid && !E.rtc.y2k && E.rtc.year == 2022 && E.rtc.hundredths == 72);
    CHECK_NEAR(E.bt_range_m[3], 13.0 + 655.36, 1e-9);
    CHECK_NEAR(E.beam_angle_deg, 30.0, 0);
    /* an old clock of the last century */
    s.year = 98;
    begin();
    add_standard(&s);
    n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && E.rtc.year == 1998);
    /* the Ocean Surveyor's lowest frequency code, 110 */
    s.cfg_lsb = 0x4E;
    begin();
    add_standard(&s);
    n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && E.frequency_khz == 38);
    /* a long leader whose Y2K bytes are zero (firmware without that clock):
     * the old clock, not the year 17 */
    s = workhorse();
    s.century = 0;
    begin();
    add_standard(&s);
    n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && !E.rtc.y2k && E.rtc.year == 2017);
    CHECK(pd0_rtc_utime(&E.rtc) > 0);
    /* a Pathfinder's 77-byte leader: spare where the Y2K clock would be, so
     * bytes there that are not that clock (its year not the old clock's) are
     * not read as one */
    s = workhorse();
    s.variable_len = 77;
    begin();
    add_standard(&s);
    types_buf[type_off[1] + 58] = 63; /* "2063" */
    n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && !E.rtc.y2k && E.rtc.year == 2017);
    /* and its 24-bit length: the byte after the 16 bits is their MSB */
    s = workhorse();
    begin();
    add_standard(&s);
    n = finish(0x7F, B);
    B[4] = 2; /* 128 kB more than the 16 bits say: longer than any unit sends */
    CHECK(pd0_decode(B, n, &E) == PD0_BAD_LENGTH);
}

static void test_sentinel_v_and_beam_counts(void)
{
    shape s = workhorse();
    s.fixed_len = 60;
    s.variable_len = 66;
    s.cfg_msb = 0x57;    /* "other" angle: the byte at 59 */
    s.angle_byte = 25;
    s.ex = 0;            /* beam */
    s.bt_len = 0;
    begin();
    add_standard(&s);
    add(0x0A00, 170);
    add(0x0F01, 40);
    add(0x3200, 34);
    add(0x7000, 16);
    add(0x7001, 58);
    add(0x7004, 10);
    size_t n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK(E.unknown_types == 6 && E.beam_angle_deg == 25 && !E.has_bottom_track);
    pd0_mounting m;
    pd0_mounting_default(&m);
    auv_dvl_t d;
    pd0_to_dvl(&E, &m, &d);
    CHECK(d.mode == AUV_DVL_T_MODE_WATER_TRACK);
    /* the leader's number of beams is the beams the velocity uses, not the
     * data's layout: with 5 or 3 the profile is the same four values a cell
     * (read with that count as the stride it would be misread, or cut short) */
    double v4[3];
    memcpy(v4, d.velocity_mps, sizeof v4);
    for (int beams = 3; beams <= 5; beams += 2) {
        s.beams = beams;
        begin();
        add_standard(&s);
        n = finish(0x7F, B);
        CHECK(pd0_decode(B, n, &E) == PD0_OK && E.n_beams == beams);
        CHECK_NEAR(E.velocity_mps[9][3], (400 + 9) * 1e-3, 1e-12);
        CHECK_NEAR(E.velocity_mps[1][0], (100 + 1) * 1e-3, 1e-12);
        pd0_to_dvl(&E, &m, &d);
        CHECK(d.mode == AUV_DVL_T_MODE_WATER_TRACK);
        for (int i = 0; i < 3; i++)
            CHECK_NEAR(d.velocity_mps[i], v4[i], 1e-12);
    }
    /* three beams in use, beam 4 marked bad: the 3-beam solution (EX allows it) */
    s.vel[3] = PD0_INVALID_VELOCITY;
    s.beams = 3;
    s.ex = 0x02;
    begin();
    add_standard(&s);
    n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && E.three_beam);
    pd0_to_dvl(&E, &m, &d);
    CHECK(d.mode == AUV_DVL_T_MODE_WATER_TRACK && d.error_velocity_mps == 0);
}

static void test_long_ensemble_and_no_cells(void)
{
    /* a length field over 16 kB is PD0 all the same */
    shape s = workhorse();
    begin();
    add_standard(&s);
    add(0x2100, 30000);
    size_t n = finish(0x7F, B);
    CHECK(n > 30000);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && E.unknown_types == 1);
    pd0_framer f;
    pd0_framer_init(&f);
    int refused[PD0_RESULT_COUNT] = {0};
    CHECK(frame_all(&f, B, n, 1000, refused) == 1 && no_refusals(refused));
    /* bottom track only (no cells pinged): the profile types hold their IDs */
    s.cells = 0;
    begin();
    add_standard(&s);
    n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK && E.n_cells == 0 && E.has_bottom_track);
}

static void test_count_restarted_one_back(void)
{
    /* WinRiver II: ensemble 127, then 127 again three minutes later */
    shape s = workhorse();
    s.number = 127;
    begin();
    add_standard(&s);
    size_t n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    pd0_continuity c = {0};
    CHECK(pd0_continuity_update(&c, E.ensemble_number, pd0_rtc_utime(&E.rtc)) == 0);
    /* the same bytes again: a repeat */
    CHECK(pd0_continuity_update(&c, E.ensemble_number, pd0_rtc_utime(&E.rtc)) == -1);
    s.second = 29;
    begin();
    add_standard(&s);
    n = finish(0x7F, B);
    CHECK(pd0_decode(B, n, &E) == PD0_OK);
    CHECK(pd0_continuity_update(&c, E.ensemble_number, pd0_rtc_utime(&E.rtc)) == -2);
    CHECK(pd0_continuity_update(&c, 128, pd0_rtc_utime(&E.rtc) + 1000000) == 0);
    CHECK(c.repeats == 1 && c.restarts == 1 && c.in_order == 2);
}

static const unit_test tests[] = {
    {"pd0_winriver_many_types_and_cells", test_winriver_many_types_and_cells},
    {"pd0_waves_packets_between_ensembles", test_waves_packets_between_ensembles},
    {"pd0_ocean_surveyor_leaders", test_ocean_surveyor_leaders},
    {"pd0_sentinel_v_and_beam_counts", test_sentinel_v_and_beam_counts},
    {"pd0_long_ensemble_and_no_cells", test_long_ensemble_and_no_cells},
    {"pd0_count_restarted_one_back", test_count_restarted_one_back},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_pd0_shapes(void) { unit_register_list(tests); }
