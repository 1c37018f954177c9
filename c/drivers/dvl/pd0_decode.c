/* PD0 decoding of one ensemble: the fixed and variable leaders, the profile
 * and bottom track, at the byte positions of the Workhorse/Pathfinder
 * "Output Data Format" (positions below count from 1 at the ID, as there).
 * A field is read only when its data type is long enough to hold it. */
#include <math.h>
#include <string.h>

#include "drivers/dvl/pd0.h"

pd0_result pd0__check_whole(const uint8_t *p, size_t n);
size_t pd0__length(const uint8_t *p);

static unsigned u16(const uint8_t *p) { return (unsigned)p[0] | (unsigned)p[1] << 8; }
static int s16(const uint8_t *p) { return (int16_t)u16(p); }
/* byte at manual position `pos` (1-based) of a data type starting at d */
#define AT(d, pos) ((d)[(pos) - 1])
#define U16(d, pos) u16((d) + (pos) - 1)
#define S16(d, pos) s16((d) + (pos) - 1)

enum { FIXED = 0x0000, VARIABLE = 0x0080, VELOCITY = 0x0100, CORRELATION = 0x0200, INTENSITY = 0x0300,
       PERCENT_GOOD = 0x0400, BOTTOM = 0x0600 };

/* The shortest fixed leader read here runs to the transmit lag distance (42
 * bytes, every Workhorse firmware); the serial number and the beam angle byte
 * (55-59) came later and are read when present. */
#define FIXED_MIN 42
#define VARIABLE_MIN 28 /* through the temperature */
#define VARIABLE_Y2K 65 /* the century clock at 58-65 */
#define BOTTOM_MIN 44   /* through the per-beam percent good */
#define BOTTOM_MSB 81   /* the range MSB bytes at 78-81 */

static pd0_result fixed_leader(const uint8_t *d, size_t len, pd0_ensemble *e)
{
    if (len < FIXED_MIN)
        return PD0_SHORT_TYPE;
    e->fw_version = AT(d, 3);
    e->fw_revision = AT(d, 4);
    e->system_config = (uint16_t)U16(d, 5);
    unsigned lsb = AT(d, 5), msb = AT(d, 6);
    static const int khz[8] = {75, 150, 300, 600, 1200, 2400, 38, 0}; /* 110: an Ocean Surveyor 38 */
    e->frequency_khz = khz[lsb & 7];
    e->convex = (lsb >> 3) & 1;
    e->facing_up = (lsb >> 7) & 1;
    static const double angle[3] = {15.0, 20.0, 30.0};
    if ((msb & 3) != 3) {
        e->beam_angle_deg = angle[msb & 3];
    } else {
        /* "other": the angle byte at 59, where the leader has it */
        if (len < 59 || AT(d, 59) == 0 || AT(d, 59) >= 60)
            return PD0_BAD_BEAM_ANGLE;
        e->beam_angle_deg = AT(d, 59);
    }
    e->n_beams = AT(d, 9);
    e->n_cells = AT(d, 10); /* a byte: never over PD0_MAX_CELLS; 0 when only bottom track is pinged */
    if (e->n_beams < 1 || e->n_beams > PD0_MAX_BEAMS)
        return PD0_BAD_BEAMS;
    e->pings_per_ensemble = (int)U16(d, 11);
    e->cell_size_m = U16(d, 13) * 0.01;
    e->blank_m = U16(d, 15) * 0.01;
    uint8_t ex = AT(d, 26);
    e->coord_transform = ex;
    e->frame = (pd0_frame)((ex >> 3) & 3);
    e->tilts_used = (ex >> 2) & 1;
    e->three_beam = (ex >> 1) & 1;
    e->bin_mapping = ex & 1;
    e->heading_alignment_deg = S16(d, 27) * 0.01;
    e->heading_bias_deg = S16(d, 29) * 0.01;
    e->sensor_source = AT(d, 31);
    e->sensors_available = AT(d, 32);
    e->bin1_distance_m = U16(d, 33) * 0.01;
    if (len >= 58)
        e->serial_number = (uint32_t)U16(d, 55) | (uint32_t)U16(d, 57) << 16;
    return PD0_OK;
}

static int days_in_month(int y, int m)
{
    static const int dm[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    int leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    return dm[m - 1] + (m == 2 && leap);
}

static void set_rtc(pd0_rtc *t, int year, const uint8_t *c, int y2k)
{
    t->year = year;
    t->month = c[1];
    t->day = c[2];
    t->hour = c[3];
    t->minute = c[4];
    t->second = c[5];
    t->hundredths = c[6];
    t->y2k = y2k;
    t->valid = t->month >= 1 && t->month <= 12 && t->day >= 1 && t->day <= days_in_month(year, t->month) &&
               t->hour < 24 && t->minute < 60 && t->second < 60 && t->hundredths < 100;
}

/* The Y2K clock's century byte where a unit has one (19 or 20); firmware
 * that leaves the clock's bytes zero has not, nor has a Pathfinder, whose
 * leader is as long but spare there: the clock is read when its century is
 * one and its year the old clock's. */
#define CENTURY_OK(c) ((c) >= 19 && (c) <= 21)
/* The old clock's two-digit year: 80..99 were the 1900s (RDI's units date
 * from 1991), the rest this century. */
#define OLD_CLOCK_YEAR(yy) ((yy) >= 80 ? 1900 + (yy) : 2000 + (yy))

static pd0_result variable_leader(const uint8_t *d, size_t len, pd0_ensemble *e)
{
    if (len < VARIABLE_MIN)
        return PD0_SHORT_TYPE;
    e->ensemble_number = (uint32_t)U16(d, 3) | (uint32_t)AT(d, 12) << 16;
    /* the 2-digit year of the old clock (5-11); the Y2K clock (58-65:
     * century, year, month, ... hundredths) says the century outright, and
     * is the one read where the leader has it (an Ocean Surveyor's 60-byte
     * leader has not) */
    set_rtc(&e->rtc, OLD_CLOCK_YEAR(AT(d, 5)), d + 4, 0);
    if (len >= VARIABLE_Y2K && CENTURY_OK(AT(d, 58)) && AT(d, 59) == AT(d, 5))
        set_rtc(&e->rtc, AT(d, 58) * 100 + AT(d, 59), d + 58, 1);
    e->bit_result = (uint16_t)U16(d, 13);
    e->sound_speed_mps = U16(d, 15);
    e->depth_m = U16(d, 17) * 0.1;
    e->heading_deg = U16(d, 19) * 0.01;
    e->pitch_deg = S16(d, 21) * 0.01;
    e->roll_deg = S16(d, 23) * 0.01;
    e->salinity_ppt = U16(d, 25);
    e->temperature_c = S16(d, 27) * 0.01;
    if (e->heading_deg >= 360.0 || fabs(e->pitch_deg) > 90.0 || fabs(e->roll_deg) > 180.0)
        return PD0_BAD_ATTITUDE;
    return PD0_OK;
}

/* Velocity, correlation, intensity and percent good: [cell][beam] after the ID. */
static pd0_result profile(const uint8_t *d, size_t len, unsigned id, pd0_ensemble *e)
{
    size_t per = (size_t)PD0_PROFILE_BEAMS * (size_t)e->n_cells;
    size_t width = id == VELOCITY ? 2 : 1;
    if (len < 2 + per * width)
        return PD0_SHORT_TYPE;
    const uint8_t *v = d + 2;
    for (int c = 0; c < e->n_cells; c++)
        for (int b = 0; b < PD0_PROFILE_BEAMS; b++, v += width) {
            switch (id) {
            case VELOCITY:
                e->velocity_mps[c][b] = s16(v) == PD0_INVALID_VELOCITY ? NAN : s16(v) * 0.001;
                break;
            case CORRELATION: e->correlation[c][b] = *v; break;
            case INTENSITY: e->intensity[c][b] = *v; break;
            default: e->percent_good[c][b] = *v; break;
            }
        }
    *(id == VELOCITY ? &e->has_velocity
      : id == CORRELATION ? &e->has_correlation
      : id == INTENSITY ? &e->has_intensity
                        : &e->has_percent_good) = 1;
    return PD0_OK;
}

static pd0_result bottom_track(const uint8_t *d, size_t len, pd0_ensemble *e)
{
    if (len < BOTTOM_MIN)
        return PD0_SHORT_TYPE;
    e->has_bottom_track = 1;
    e->bt_pings = (int)U16(d, 3);
    for (int b = 0; b < PD0_BT_BEAMS; b++) {
        /* range: 16 bits of cm at 17.., and an MSB byte (65536 cm) at 78.. */
        uint32_t cm = U16(d, 17 + 2 * b);
        if (len >= BOTTOM_MSB)
            cm |= (uint32_t)AT(d, 78 + b) << 16;
        e->bt_range_m[b] = cm == 0 ? -1.0 : cm * 0.01; /* 0: no bottom in that beam */
        int v = S16(d, 25 + 2 * b);
        e->bt_velocity_mps[b] = v == PD0_INVALID_VELOCITY ? NAN : v * 0.001;
        e->bt_correlation[b] = AT(d, 33 + b);
        e->bt_eval_amplitude[b] = AT(d, 37 + b);
        e->bt_percent_good[b] = AT(d, 41 + b);
    }
    return PD0_OK;
}

pd0_result pd0_decode(const uint8_t *p, size_t n, pd0_ensemble *e)
{
    memset(e, 0, sizeof *e);
    for (int c = 0; c < PD0_MAX_CELLS; c++)
        for (int b = 0; b < PD0_PROFILE_BEAMS; b++)
            e->velocity_mps[c][b] = NAN;
    for (int b = 0; b < PD0_BT_BEAMS; b++) {
        e->bt_range_m[b] = -1.0;
        e->bt_velocity_mps[b] = NAN;
    }
    pd0_result r = pd0__check_whole(p, n);
    if (r != PD0_OK)
        return r;
    size_t nbytes = pd0__length(p), ntypes = p[5];
    size_t off[PD0_MAX_TYPES + 1];
    for (size_t i = 0; i < ntypes; i++)
        off[i] = u16(p + 6 + 2 * i);
    off[ntypes] = nbytes;
    /* the fixed leader first: the profile's size depends on it */
    int fixed = -1, variable = -1;
    for (size_t i = 0; i < ntypes; i++) {
        unsigned id = u16(p + off[i]);
        int *slot = id == FIXED ? &fixed : id == VARIABLE ? &variable : NULL;
        if (slot && *slot >= 0)
            return PD0_DUPLICATE_TYPE;
        if (slot)
            *slot = (int)i;
    }
    if (fixed < 0)
        return PD0_NO_FIXED_LEADER;
    if (variable < 0)
        return PD0_NO_VARIABLE_LEADER;
    r = fixed_leader(p + off[fixed], off[fixed + 1] - off[fixed], e);
    if (r != PD0_OK)
        return r;
    unsigned seen = 0; /* one bit per known data type */
    for (size_t i = 0; i < ntypes; i++) {
        const uint8_t *d = p + off[i];
        size_t len = off[i + 1] - off[i];
        unsigned id = u16(d), bit;
        switch (id) {
        case FIXED: continue;
        case VARIABLE: bit = 1; r = variable_leader(d, len, e); break;
        case VELOCITY: bit = 2; r = profile(d, len, id, e); break;
        case CORRELATION: bit = 4; r = profile(d, len, id, e); break;
        case INTENSITY: bit = 8; r = profile(d, len, id, e); break;
        case PERCENT_GOOD: bit = 16; r = profile(d, len, id, e); break;
        case BOTTOM: bit = 32; r = bottom_track(d, len, e); break;
        default: e->unknown_types++; continue;
        }
        if (seen & bit)
            return PD0_DUPLICATE_TYPE;
        seen |= bit;
        if (r != PD0_OK)
            return r;
    }
    return PD0_OK;
}

/* Days since 1970-01-01 of a civil date (proleptic Gregorian), without
 * timegm's dependence on the process's time zone. */
static int64_t days_from_civil(int y, int m, int d)
{
    y -= m <= 2;
    int64_t era = (y >= 0 ? y : y - 399) / 400;
    int64_t yoe = y - era * 400;
    int64_t doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    int64_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

int64_t pd0_rtc_utime(const pd0_rtc *t)
{
    if (!t->valid)
        return 0;
    int64_t s = days_from_civil(t->year, t->month, t->day) * 86400 + t->hour * 3600 + t->minute * 60 + t->second;
    return s * 1000000 + (int64_t)t->hundredths * 10000;
}

long pd0_continuity_update(pd0_continuity *c, uint32_t number, int64_t device_utime)
{
    number &= 0xFFFFFF;
    int64_t last_utime = c->last_utime;
    c->last_utime = device_utime;
    if (!c->have) {
        c->have = 1;
        c->last = number;
        c->in_order++;
        return 0;
    }
    uint32_t d = (number - c->last) & 0xFFFFFF;
    c->last = number;
    if (d == 1) {
        c->in_order++;
        return 0;
    }
    /* the same number: the same ensemble again (sent twice, or copied)
     * unless both clocks say it came a second or more later: then the count
     * was restarted one back (WinRiver II resuming a transect) */
    if (d == 0 && (device_utime == 0 || last_utime == 0 || device_utime - last_utime < PD0_SAME_ENSEMBLE_US)) {
        c->repeats++;
        return -1;
    }
    if (d == 0) {
        c->restarts++;
        return -2;
    }
    if (d < 0x800000) { /* forward: the ones between were lost */
        c->gaps++;
        c->missed += d - 1;
        return (long)(d - 1);
    }
    c->restarts++; /* backward: a restarted count */
    return -2;
}

const char *pd0_frame_name(pd0_frame f)
{
    static const char *const n[4] = {"beam", "instrument", "ship", "earth"};
    return (unsigned)f < 4 ? n[f] : "?";
}
