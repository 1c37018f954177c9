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
 *
 * Sign conventions differ between makers; the published PASHR convention is
 * roll positive with the starboard side down (port up) and pitch positive bow up,
 * which are the project's (ahrs_t). A device that differs is configured with
 * the signs (ahrs_nmea_config), never patched in code.
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
    int has_heading, has_attitude, has_time, has_accuracy, has_heave;
    double heading_rad;          /* [0, 2 pi), true */
    double roll_rad, pitch_rad;  /* project convention */
    double heave_m;
    double time_of_day_s;        /* UTC seconds of the day, from PASHR */
    double roll_sigma_rad, pitch_sigma_rad, heading_sigma_rad;
    int gnss_quality;            /* -1 when absent */
    int imu_status;              /* -1 when absent (older firmware) */
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
    AHRS_NMEA_RESULT_COUNT
} ahrs_nmea_result;

const char *ahrs_nmea_result_name(ahrs_nmea_result r);

/* One sentence into *out (cleared first). */
ahrs_nmea_result ahrs_nmea_decode(const nmea_sentence *s, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out);

#endif
