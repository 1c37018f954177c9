/* Teledyne RDI PD0, the binary ensemble of Workhorse, Pathfinder, Tasman and
 * Navigator DVLs and of RDI's ADCPs (Rio Grande, Ocean Surveyor, RiverPro,
 * Sentinel V; the "Commands and Output Data Format" manuals): an incremental
 * framer over any byte stream, a strict decoder of one ensemble,
 * ensemble-number continuity, and the ensemble turned into the project's
 * dvl_t (docs/drivers.md, "DVL: Teledyne RDI PD0").
 * No LCM calls, no I/O, no allocation: bytes in, checked values out.
 *
 * An ensemble, all integers little-endian:
 *   header    7F 7F, the number of bytes up to the checksum (16 bits, and the
 *             next byte, "spare" in the Workhorse's manual, their MSB in the
 *             Pathfinder's), the number of data types N (one byte: up to 255), then N
 *             offsets (16 bits each, from the first 7F) of the data types,
 *             each starting with its 16-bit ID; the first data type follows
 *             the offsets;
 *   data      0x0000 fixed leader, 0x0080 variable leader, 0x0100 velocity,
 *             0x0200 correlation, 0x0300 echo intensity, 0x0400 percent good,
 *             0x0600 bottom track; any other ID (navigation 0x2000-0x2104,
 *             NMEA 0x2022, fixed attitude 0x3000-0x30FF, beam 5 0x0A00-0x0F01,
 *             Sentinel V 0x7000-0x7004, surface layer 0x0010-0x0510, ...) is
 *             skipped by its offset and counted;
 *   checksum  the sum of every byte before it, modulo 65536 (16 bits).
 * Between ensembles a Workhorse with the waves option sends waves packets,
 * framed the same way but led by 7F 79: the framer checks and skips them.
 *
 * Every refusal has a reason (pd0_result_name), which the driver counts. */
#ifndef DRIVERS_PD0_H
#define DRIVERS_PD0_H

#include <stddef.h>
#include <stdint.h>

/* The longest ensemble taken (no unit sends one near it: 7.3 kB is the
 * longest seen, WinRiver II's); the framer holds one at most. A length over
 * it (the 24-bit length allows 16 MB) is refused as a bad length. */
#define PD0_MAX_ENSEMBLE 65535
#define PD0_MAX_TYPES 255 /* the header's one-byte count (WinRiver II sends 60+ with its NMEA) */
/* The fixed leader's number of beams is the beams used for the velocity
 * (3 when a unit solves with three, 4, 5 with a vertical beam), not the
 * layout of the data: the profile types hold four values per cell whatever
 * it says ("2 bytes + 8 bytes per depth cell" for the velocity; a Sentinel V's
 * fifth beam has data types of its own), and bottom track four per type. */
#define PD0_MAX_BEAMS 5
#define PD0_PROFILE_BEAMS 4
#define PD0_BT_BEAMS 4
/* The fixed leader's one-byte cell count (WN: 1..128 on a Workhorse, more
 * on a Rio Grande or Ocean Surveyor, 132 seen): all of it is decoded. */
#define PD0_MAX_CELLS 255
#define PD0_INVALID_VELOCITY (-32768) /* the raw marker of a bad velocity */

typedef enum {
    PD0_OK = 0,
    PD0_BAD_CHECKSUM,       /* the sum does not match */
    PD0_BAD_LENGTH,         /* the length field: shorter than its header and offsets, or over
                             * PD0_MAX_ENSEMBLE */
    PD0_BAD_HEADER,         /* no data types */
    PD0_TRUNCATED,          /* fewer bytes than the length says: a buffer, or a stream that went quiet */
    PD0_BAD_OFFSET,         /* the first data type not right after the offsets, an offset past the end, or
                             * not increasing: known before the whole ensemble is (a false 7F 7F is
                             * refused early, not held for the bytes its length says) */
    PD0_SHORT_TYPE,         /* a data type shorter than its fields (its beams x cells) */
    PD0_DUPLICATE_TYPE,     /* the same data type twice */
    PD0_NO_FIXED_LEADER,
    PD0_NO_VARIABLE_LEADER,
    PD0_BAD_BEAMS,          /* 0 beams, or more than PD0_MAX_BEAMS */
    PD0_BAD_BEAM_ANGLE,     /* "other" in the system configuration and no usable angle byte */
    PD0_BAD_ATTITUDE,       /* heading >= 360, |pitch| > 90 or |roll| > 180 degrees */
    PD0_RESULT_COUNT
} pd0_result;

/* "bad checksum", "truncated ensemble", "offset outside ensemble", ... */
const char *pd0_result_name(pd0_result r);

/* The 16-bit sum of n bytes. */
uint16_t pd0_checksum(const uint8_t *p, size_t n);

/* ------------------------------------------------------------------ framer */
typedef struct {
    uint8_t buf[PD0_MAX_ENSEMBLE + 2];
    size_t start, len;       /* held bytes are buf[start .. len) */
    size_t deliver;          /* an ensemble handed out last call: dropped on the next */
    size_t need;             /* the held header waits for this many bytes (0: not known), so a
                              * read of a few bytes does not check its offset table again */
    uint64_t garbage_bytes;  /* bytes skipped while looking for a header */
    uint64_t waves_packets;  /* 7F 79 packets (a Workhorse's waves option) checked and skipped */
} pd0_framer;

void pd0_framer_init(pd0_framer *f);

/* Takes bytes of the stream. Returns PD0_OK with *ens / *ens_len set to one
 * whole ensemble (header to checksum, checksum verified, offsets inside it;
 * valid until the next call), a refusal reason, or -1 when every byte given
 * was taken and nothing more is complete. A waves packet (7F 79, its sum
 * good) is skipped whole and counted in waves_packets; a 7F 79 that is not
 * one is garbage. *used is how many of the n bytes
 * were taken; call again with the rest (n may be 0) until it returns -1:
 *
 *     while ((r = pd0_framer_push(&f, p, n, &used, &e, &len)) != -1) {
 *         p += used; n -= used;  ...  }
 *
 * After a bad length, header or checksum it resynchronises one byte after
 * the refused header (an ensemble may start inside a broken one). It never
 * reads past the bytes given, and never holds more than one ensemble. */
int pd0_framer_push(pd0_framer *f, const uint8_t *data, size_t n, size_t *used, const uint8_t **ens,
                    size_t *ens_len);

/* The stream went quiet (a read timeout) or ended: a partial ensemble held is
 * dropped. Returns PD0_TRUNCATED if one was (the device stopped mid-ensemble),
 * else -1. Bytes that were not yet a header count as garbage. */
int pd0_framer_flush(pd0_framer *f);

/* ------------------------------------------------------------------ decoder */
typedef enum { PD0_FRAME_BEAM = 0, PD0_FRAME_INSTRUMENT = 1, PD0_FRAME_SHIP = 2, PD0_FRAME_EARTH = 3 } pd0_frame;
const char *pd0_frame_name(pd0_frame f); /* "beam", "instrument", "ship", "earth" */

typedef struct {
    int valid;               /* month 1..12, day in its month, hour < 24, ... */
    int year;                /* four digits: the Y2K clock where the leader has it, else 2000 + yy */
    int month, day, hour, minute, second, hundredths;
    int y2k;                 /* 1: from the Y2K (century) clock bytes */
} pd0_rtc;

typedef struct {
    /* fixed leader (0x0000) */
    int fw_version, fw_revision;
    uint16_t system_config;  /* LSB: frequency, convex, facing up; MSB: beam angle, beams */
    int frequency_khz;       /* 38 .. 2400; 0 if the code is not a published one */
    int convex;              /* 1 convex transducer, 0 concave */
    int facing_up;
    double beam_angle_deg;   /* 15, 20, 30, or the fixed leader's angle byte for "other" */
    int n_beams;             /* beams used for the velocity (the profile has PD0_PROFILE_BEAMS) */
    int n_cells, pings_per_ensemble;
    double cell_size_m, blank_m, bin1_distance_m;
    uint8_t coord_transform; /* the EX byte */
    pd0_frame frame;         /* from EX bits 3-4 */
    int tilts_used;          /* EX bit 2: pitch and roll used in the ship and earth frames */
    int three_beam;          /* EX bit 1: 3-beam solutions allowed */
    int bin_mapping;         /* EX bit 0 */
    double heading_alignment_deg, heading_bias_deg; /* EA, EB */
    uint8_t sensor_source, sensors_available;       /* EZ bits: 0x08 pitch from its own tilt sensor */
    uint32_t serial_number;  /* 0 when the leader is too short to carry it */

    /* variable leader (0x0080) */
    uint32_t ensemble_number; /* 24 bits: the 16-bit number and its MSB byte */
    pd0_rtc rtc;
    uint16_t bit_result;
    double sound_speed_mps, depth_m, heading_deg, pitch_deg, roll_deg, salinity_ppt, temperature_c;

    /* profile: [cell][beam]; velocities in the frame above, NAN where marked invalid */
    int has_velocity, has_correlation, has_intensity, has_percent_good;
    double velocity_mps[PD0_MAX_CELLS][PD0_PROFILE_BEAMS];
    uint8_t correlation[PD0_MAX_CELLS][PD0_PROFILE_BEAMS];
    uint8_t intensity[PD0_MAX_CELLS][PD0_PROFILE_BEAMS];
    uint8_t percent_good[PD0_MAX_CELLS][PD0_PROFILE_BEAMS];

    /* bottom track (0x0600); per beam whatever the frame, velocities in the frame */
    int has_bottom_track;
    int bt_pings;
    double bt_range_m[PD0_BT_BEAMS];    /* RDI's BT range with its MSB byte where the data type has them:
                                         * the VERTICAL range seen along the beam (slant x cos(beam
                                         * angle)), not corrected for pitch and roll; -1 where 0 (no
                                         * bottom) */
    double bt_velocity_mps[PD0_BT_BEAMS]; /* NAN where marked invalid */
    uint8_t bt_correlation[PD0_BT_BEAMS], bt_eval_amplitude[PD0_BT_BEAMS], bt_percent_good[PD0_BT_BEAMS];

    int unknown_types;       /* data types skipped (navigation, NMEA, status, beam 5, ...) */
} pd0_ensemble;

/* Decodes one whole ensemble (n bytes from its first 7F; n may exceed it:
 * bytes after the checksum are ignored). Checks everything the framer does
 * too, so it is safe on any buffer. *e is zeroed first. */
pd0_result pd0_decode(const uint8_t *p, size_t n, pd0_ensemble *e);

/* Device time of the RTC [us since 1970, the device's clock, UTC if it was
 * set so]; 0 if it is not valid. */
int64_t pd0_rtc_utime(const pd0_rtc *t);

/* ------------------------------------------------------------------ continuity */
typedef struct {
    int have;
    uint32_t last;
    int64_t last_utime;      /* the device time of the last number (pd0_rtc_utime), 0 if none */
    uint64_t in_order, gaps, missed, repeats, restarts;
} pd0_continuity;

/* The same number within this much device time is the same ensemble again. */
#define PD0_SAME_ENSEMBLE_US 1000000

/* Returns 0 in order (the first number too), the count missed after a gap,
 * -1 for a repeat of the last ensemble (its number again within
 * PD0_SAME_ENSEMBLE_US of its device time, or with no time to tell them
 * apart), -2 for a step back or the same number a second or more later (the
 * device restarted its count: WinRiver II numbers the first ensemble of a
 * resumed transect as the last one of the previous, a new ping all the
 * same). Numbers are 24 bits and wrap from 0xFFFFFF to 0. device_utime:
 * pd0_rtc_utime of the ensemble, 0 if none. */
long pd0_continuity_update(pd0_continuity *c, uint32_t number, int64_t device_utime);

/* ------------------------------------------------------------------ dvl_t */
struct _auv_dvl_t;

/* How the DVL sits on the vehicle: the rotation from the vehicle body to the
 * DVL's own axes (ZYX Euler angles, radians). All zero: beam 3 forward,
 * looking down, RDI's X axis to starboard (the default). */
typedef struct {
    double yaw_rad, pitch_rad, roll_rad;
    double velocity_sigma_mps; /* published 1-sigma per axis when the velocity is good */
} pd0_mounting;

void pd0_mounting_default(pd0_mounting *m);

/* Fills the measurement fields of *out (not utime and vehicle, the driver's):
 * mode, velocity_mps in the body frame (x fwd, y stbd, z down), altitude_m,
 * beam_range_m in the device's beam order, and the device fields (frame,
 * ensemble number, device time, error velocity, temperature, salinity,
 * sound speed). Bottom lock when the bottom-track velocity is good, water
 * track from the profile otherwise, MODE_NONE when neither is. */
void pd0_to_dvl(const pd0_ensemble *e, const pd0_mounting *m, struct _auv_dvl_t *out);

/* The pieces, for tests and tools: the vehicle's velocity in body axes from
 * four values in the ensemble's frame (the PD0 sense: the bottom's or the
 * water's velocity relative to the DVL; beams 1-4 of a Janus head in the beam
 * frame, X Y Z and the error velocity in the others: NAN where there is none);
 * returns 0 if it cannot (too few good values). *err_mps: the error velocity,
 * 0 when not given. */
int pd0_body_velocity(const pd0_ensemble *e, const pd0_mounting *m, const double v4[4], double body[3],
                      double *err_mps);
/* altitude_m from the bottom-track ranges (see pd0_dvl.c); -1 if fewer than 3. */
double pd0_altitude(const pd0_ensemble *e);

#endif
