/* Heading and attitude over NMEA 0183, for a compass or AHRS on a serial line:
 *
 *   $--HDT,hhh.h,T*hh          heading, true (HE: gyro, HC: magnetic compass
 *                              corrected to true, or any talker)
 *   $PASHR,hhmmss.sss,hhh.hh,T,rrr.rr,ppp.pp,xxx.xx,a.aaa,b.bbb,c.ccc,d,e*hh
 *                              the RT300/TSS-style attitude sentence: UTC time,
 *                              true heading, roll, pitch, heave [m], the roll,
 *                              pitch and heading accuracies (1 sigma, deg), the
 *                              GNSS quality (0-6) and the IMU alignment status
 *                              (0-4, the last field: older firmware omits it)
 *   $PRDID,ppp.pp,rrr.rr,hhh.hh*hh
 *                              Teledyne RDI's attitude sentence (an ADCP/DVL's
 *                              input, written by gyrocompasses and INS): pitch,
 *                              roll, true heading [deg]; no time, no rates
 *   $VNYMR,yyy.yyy,ppp.ppp,rrr.rrr,mx,my,mz,ax,ay,az,gx,gy,gz*hh
 *                              VectorNav's "Yaw, Pitch, Roll, Magnetic,
 *                              Acceleration and Angular Rates" (register 27,
 *                              async header YMR; VN-100 User Manual UM001,
 *                              7.2.3): yaw, pitch, roll [deg] as a 3-2-1 Euler
 *                              sequence from NED, yaw in -180..180; the
 *                              compensated magnetic field [Gauss], acceleration
 *                              [m/s^2] and angular rates [rad/s], body x, y, z
 *
 * Sign conventions differ between makers; the published PASHR convention is
 * roll positive with the starboard side down (port up) and pitch positive bow up,
 * which are the project's (ahrs_t). VectorNav's body frame (x forward, y
 * starboard, z down) and its Euler sequence are the project's too: yaw is the
 * heading, and the rates about x, y, z are p, q, r. A device that differs is
 * configured with the signs (ahrs_nmea_config; roll's sign also turns p, pitch's
 * q: a flipped axis flips its rate), never patched in code.
 *
 * No LCM, no I/O: a checked sentence in, a reading or a refusal reason out. */
#ifndef DRIVERS_AHRS_NMEA_H
#define DRIVERS_AHRS_NMEA_H

#include "drivers/common/nmea.h"

typedef struct {
    int roll_sign, pitch_sign; /* +1 or -1: the device's sign times this is the project's */
    double heading_offset_deg; /* added to every heading: the mounting's yaw misalignment */
} ahrs_nmea_config;

#define AHRS_NMEA_DEFAULTS ((ahrs_nmea_config){.roll_sign = 1, .pitch_sign = 1, .heading_offset_deg = 0.0})

typedef struct {
    int has_heading, has_attitude, has_time, has_accuracy, has_heave, has_rates, has_imu;
    double heading_rad;          /* [0, 2 pi), true */
    double roll_rad, pitch_rad;  /* project convention */
    double heave_m;
    double time_of_day_s;        /* UTC seconds of the day, from PASHR */
    double roll_sigma_rad, pitch_sigma_rad, heading_sigma_rad;
    int gnss_quality;            /* -1 when absent */
    int imu_status;              /* -1 when absent (older firmware) */
    double p_radps, q_radps, r_radps; /* body rates (VNYMR), project signs */
    double accel_mps2[3];        /* VNYMR's acceleration and magnetic field, body x, y, z, */
    double mag_gauss[3];         /* as the device gives them (checked, not published) */
} ahrs_nmea_reading;

typedef enum {
    AHRS_NMEA_OK = 0,
    AHRS_NMEA_NOT_MINE,          /* another sentence: not counted as an error */
    AHRS_NMEA_MISSING_FIELD,
    AHRS_NMEA_BAD_FIELD,         /* malformed number */
    AHRS_NMEA_HEADING_RANGE,     /* outside [0, 360] */
    AHRS_NMEA_NOT_TRUE,          /* the T flag absent: not a true heading */
    AHRS_NMEA_ATTITUDE_RANGE,    /* |roll| > 180 or |pitch| > 90 */
    AHRS_NMEA_ACCURACY_RANGE,    /* negative or absurd (> 180 deg) accuracy */
    AHRS_NMEA_STATUS_RANGE,      /* GNSS quality or IMU status outside their published codes */
    AHRS_NMEA_TIME_RANGE,
    AHRS_NMEA_RATE_RANGE,        /* an angular rate beyond AHRS_NMEA_MAX_RATE_RADPS */
    AHRS_NMEA_ACCEL_RANGE,       /* an acceleration beyond AHRS_NMEA_MAX_ACCEL_MPS2 */
    AHRS_NMEA_MAG_RANGE,         /* a magnetic field beyond AHRS_NMEA_MAX_MAG_GAUSS */
    AHRS_NMEA_RESULT_COUNT
} ahrs_nmea_result;

/* Beyond any AHRS's range, so a value past them is a corrupt sentence: a MEMS
 * gyro's widest is 2000 deg/s (35 rad/s), an accelerometer's 16 g, and the
 * Earth's field under 0.7 Gauss (a magnetometer saturates at a few Gauss). */
#define AHRS_NMEA_MAX_RATE_RADPS 40.0
#define AHRS_NMEA_MAX_ACCEL_MPS2 200.0
#define AHRS_NMEA_MAX_MAG_GAUSS 16.0

const char *ahrs_nmea_result_name(ahrs_nmea_result r);

/* One sentence into *out (cleared first). */
ahrs_nmea_result ahrs_nmea_decode(const nmea_sentence *s, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out);

#endif
