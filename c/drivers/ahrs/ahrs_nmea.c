#include "drivers/ahrs/ahrs_nmea.h"

#include <ctype.h>
#include <math.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)

const char *ahrs_nmea_result_name(ahrs_nmea_result r)
{
    static const char *const names[AHRS_NMEA_RESULT_COUNT] = {
        [AHRS_NMEA_OK] = "ok",
        [AHRS_NMEA_NOT_MINE] = "not a heading or attitude sentence",
        [AHRS_NMEA_MISSING_FIELD] = "missing field",
        [AHRS_NMEA_BAD_FIELD] = "malformed field",
        [AHRS_NMEA_HEADING_RANGE] = "heading out of range",
        [AHRS_NMEA_NOT_TRUE] = "heading not true",
        [AHRS_NMEA_ATTITUDE_RANGE] = "attitude out of range",
        [AHRS_NMEA_ACCURACY_RANGE] = "accuracy out of range",
        [AHRS_NMEA_STATUS_RANGE] = "status out of range",
        [AHRS_NMEA_TIME_RANGE] = "time out of range",
        [AHRS_NMEA_RATE_RANGE] = "rate out of range",
        [AHRS_NMEA_ACCEL_RANGE] = "acceleration out of range",
        [AHRS_NMEA_MAG_RANGE] = "magnetic field out of range",
    };
    return (unsigned)r < AHRS_NMEA_RESULT_COUNT ? names[r] : "unknown";
}

/* A required number: 1 ok, else the refusal. */
static ahrs_nmea_result need(const nmea_sentence *s, int i, double *v)
{
    int r = nmea_field_double(s, i, v);
    return r == 1 ? AHRS_NMEA_OK : r == 0 ? AHRS_NMEA_MISSING_FIELD : AHRS_NMEA_BAD_FIELD;
}

static double wrap_2pi(double a)
{
    a = fmod(a, 2.0 * 3.14159265358979323846);
    return a < 0.0 ? a + 2.0 * 3.14159265358979323846 : a;
}

static ahrs_nmea_result heading(const nmea_sentence *s, int i, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out)
{
    double deg;
    ahrs_nmea_result r = need(s, i, &deg);
    if (r != AHRS_NMEA_OK)
        return r;
    if (!(deg >= 0.0 && deg <= 360.0))
        return AHRS_NMEA_HEADING_RANGE;
    if (i + 1 >= s->nfields || strcmp(s->field[i + 1], "T") != 0)
        return AHRS_NMEA_NOT_TRUE;
    out->heading_rad = wrap_2pi((deg + cfg->heading_offset_deg) * DEG);
    out->has_heading = 1;
    return AHRS_NMEA_OK;
}

static ahrs_nmea_result pashr(const nmea_sentence *s, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out)
{
    if (s->nfields < 10)
        return AHRS_NMEA_MISSING_FIELD;
    int t = nmea_field_time_of_day(s, 0, &out->time_of_day_s);
    if (t < 0)
        return AHRS_NMEA_TIME_RANGE;
    out->has_time = t == 1;
    ahrs_nmea_result r = heading(s, 1, cfg, out);
    if (r != AHRS_NMEA_OK)
        return r;
    double roll, pitch;
    if ((r = need(s, 3, &roll)) != AHRS_NMEA_OK || (r = need(s, 4, &pitch)) != AHRS_NMEA_OK)
        return r;
    if (fabs(roll) > 180.0 || fabs(pitch) > 90.0)
        return AHRS_NMEA_ATTITUDE_RANGE;
    out->roll_rad = cfg->roll_sign * roll * DEG;
    out->pitch_rad = cfg->pitch_sign * pitch * DEG;
    out->has_attitude = 1;
    int h = nmea_field_double(s, 5, &out->heave_m); /* "reserved" on some receivers: may be empty */
    if (h < 0 || fabs(out->heave_m) > 100.0)
        return AHRS_NMEA_BAD_FIELD;
    out->has_heave = h == 1;
    double sig[3];
    int given = 0;
    for (int k = 0; k < 3; k++) {
        int a = nmea_field_double(s, 6 + k, &sig[k]);
        if (a < 0)
            return AHRS_NMEA_BAD_FIELD;
        if (a == 1 && !(sig[k] >= 0.0 && sig[k] <= 180.0))
            return AHRS_NMEA_ACCURACY_RANGE;
        given += a;
    }
    if (given == 3) {
        out->roll_sigma_rad = sig[0] * DEG, out->pitch_sigma_rad = sig[1] * DEG, out->heading_sigma_rad = sig[2] * DEG;
        out->has_accuracy = 1;
    }
    long q = -1, imu = -1;
    if (nmea_field_int(s, 9, &q) < 0 || q > 6 || q < -1)
        return AHRS_NMEA_STATUS_RANGE;
    if (s->nfields > 10 && (nmea_field_int(s, 10, &imu) < 0 || imu > 4 || imu < -1))
        return AHRS_NMEA_STATUS_RANGE;
    out->gnss_quality = (int)q;
    out->imu_status = (int)imu;
    return AHRS_NMEA_OK;
}

/* Three required numbers from field i, each within +-max, else range. */
static ahrs_nmea_result vector3(const nmea_sentence *s, int i, double max, ahrs_nmea_result range, double v[3])
{
    for (int k = 0; k < 3; k++) {
        ahrs_nmea_result r = need(s, i + k, &v[k]);
        if (r != AHRS_NMEA_OK)
            return r;
        if (fabs(v[k]) > max)
            return range;
    }
    return AHRS_NMEA_OK;
}

static ahrs_nmea_result vnymr(const nmea_sentence *s, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out)
{
    if (s->nfields < 12)
        return AHRS_NMEA_MISSING_FIELD;
    if (s->nfields > 12) /* a fixed layout: a field more is another sentence's or corrupt */
        return AHRS_NMEA_BAD_FIELD;
    double yaw, pitch, roll, rate[3];
    ahrs_nmea_result r;
    if ((r = need(s, 0, &yaw)) != AHRS_NMEA_OK || (r = need(s, 1, &pitch)) != AHRS_NMEA_OK ||
        (r = need(s, 2, &roll)) != AHRS_NMEA_OK)
        return r;
    if (fabs(yaw) > 180.0)
        return AHRS_NMEA_HEADING_RANGE;
    if (fabs(roll) > 180.0 || fabs(pitch) > 90.0)
        return AHRS_NMEA_ATTITUDE_RANGE;
    if ((r = vector3(s, 3, AHRS_NMEA_MAX_MAG_GAUSS, AHRS_NMEA_MAG_RANGE, out->mag_gauss)) != AHRS_NMEA_OK ||
        (r = vector3(s, 6, AHRS_NMEA_MAX_ACCEL_MPS2, AHRS_NMEA_ACCEL_RANGE, out->accel_mps2)) != AHRS_NMEA_OK ||
        (r = vector3(s, 9, AHRS_NMEA_MAX_RATE_RADPS, AHRS_NMEA_RATE_RANGE, rate)) != AHRS_NMEA_OK)
        return r;
    /* yaw is the heading (relative to the device's reference: magnetic north unless
     * configured for true; the offset carries the declination), wrapped to [0, 2 pi) */
    out->heading_rad = wrap_2pi((yaw + cfg->heading_offset_deg) * DEG);
    out->roll_rad = cfg->roll_sign * roll * DEG;
    out->pitch_rad = cfg->pitch_sign * pitch * DEG;
    out->p_radps = cfg->roll_sign * rate[0];
    out->q_radps = cfg->pitch_sign * rate[1];
    out->r_radps = rate[2];
    out->has_heading = out->has_attitude = out->has_rates = out->has_imu = 1;
    return AHRS_NMEA_OK;
}

/* $PRDID,ppp.pp,rrr.rr,hhh.hh: Teledyne RDI's attitude sentence (pitch, roll,
 * true heading, degrees), which gyrocompasses and INS write for an ADCP or a
 * DVL; pitch bow up and roll port up positive, the project's convention (a
 * device that differs is given its signs, as for PASHR). No time, no rates. */
static ahrs_nmea_result prdid(const nmea_sentence *s, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out)
{
    if (s->nfields < 3)
        return AHRS_NMEA_MISSING_FIELD;
    if (s->nfields > 3) /* a fixed layout: a field more is another sentence's or corrupt */
        return AHRS_NMEA_BAD_FIELD;
    double pitch, roll, deg;
    ahrs_nmea_result r;
    if ((r = need(s, 0, &pitch)) != AHRS_NMEA_OK || (r = need(s, 1, &roll)) != AHRS_NMEA_OK ||
        (r = need(s, 2, &deg)) != AHRS_NMEA_OK)
        return r;
    if (fabs(roll) > 180.0 || fabs(pitch) > 90.0)
        return AHRS_NMEA_ATTITUDE_RANGE;
    if (!(deg >= 0.0 && deg <= 360.0))
        return AHRS_NMEA_HEADING_RANGE;
    out->heading_rad = wrap_2pi((deg + cfg->heading_offset_deg) * DEG);
    out->roll_rad = cfg->roll_sign * roll * DEG;
    out->pitch_rad = cfg->pitch_sign * pitch * DEG;
    out->has_heading = out->has_attitude = 1;
    return AHRS_NMEA_OK;
}

/* HDT with its heading field empty: a gyro still settling, a GNSS compass
 * without its two fixes, says "no heading" this way; valid, and no value. */
static ahrs_nmea_result hdt(const nmea_sentence *s, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out)
{
    if (s->nfields >= 1 && !s->field[0][0])
        return AHRS_NMEA_OK;
    return heading(s, 0, cfg, out);
}

/* THS (NMEA 0183 3.0 on, HDT's successor): true heading and its mode, A
 * autonomous, E estimated (dead reckoning), M manual, S simulator, V not
 * valid. A heading marked V, or none, is no value. */
static ahrs_nmea_result ths(const nmea_sentence *s, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out)
{
    if (s->nfields < 2)
        return AHRS_NMEA_MISSING_FIELD;
    const char *mode = s->field[1];
    if (strlen(mode) != 1 || !strchr("AEMSV", mode[0]))
        return AHRS_NMEA_STATUS_RANGE;
    if (mode[0] == 'V' || !s->field[0][0])
        return AHRS_NMEA_OK;
    double deg;
    ahrs_nmea_result r = need(s, 0, &deg);
    if (r != AHRS_NMEA_OK)
        return r;
    if (!(deg >= 0.0 && deg <= 360.0))
        return AHRS_NMEA_HEADING_RANGE;
    out->heading_rad = wrap_2pi((deg + cfg->heading_offset_deg) * DEG);
    out->has_heading = 1;
    return AHRS_NMEA_OK;
}

ahrs_nmea_result ahrs_nmea_decode(const nmea_sentence *s, const ahrs_nmea_config *cfg, ahrs_nmea_reading *out)
{
    memset(out, 0, sizeof *out);
    out->gnss_quality = out->imu_status = -1;
    /* Ashtech's $PASHR family (PASHR,POS / ATT / MCA ...: a name first, not a
     * time) shares the address; only the attitude sentence is ours */
    if (!strcmp(s->type, "PASHR") && s->nfields > 0 && isalpha((unsigned char)s->field[0][0]))
        return AHRS_NMEA_NOT_MINE;
    if (!strcmp(s->type, "PASHR"))
        return pashr(s, cfg, out);
    if (!strcmp(s->type, "PRDID"))
        return prdid(s, cfg, out);
    if (s->talker[0] && !strcmp(s->type, "HDT"))
        return hdt(s, cfg, out);
    if (s->talker[0] && !strcmp(s->type, "THS"))
        return ths(s, cfg, out);
    if (!strcmp(s->talker, "VN") && !strcmp(s->type, "YMR"))
        return vnymr(s, cfg, out);
    return AHRS_NMEA_NOT_MINE;
}
