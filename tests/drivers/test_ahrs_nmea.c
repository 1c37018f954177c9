/* Unit tests of the heading and attitude sentences (c/drivers/ahrs/ahrs_nmea.c):
 * HDT from any talker, PASHR with and without its last field, the signs and
 * mounting offset, and every refusal. */
#include <math.h>
#include <string.h>

#include "drivers/ahrs/ahrs_nmea.h"
#include "../harness/unit.h"

#define DEG (3.14159265358979323846 / 180.0)

/* Formats body with its checksum and decodes it with cfg. */
static ahrs_nmea_result decode(const char *body, const ahrs_nmea_config *cfg, ahrs_nmea_reading *r)
{
    char line[NMEA_MAX_SENTENCE + 8];
    nmea_sentence s;
    if (nmea_format(line, sizeof line, body) < 0 || nmea_parse_line(line, strlen(line), 0, &s) != NMEA_OK) {
        UNIT_FAIL("not a sentence: %s", body);
        return AHRS_NMEA_RESULT_COUNT;
    }
    return ahrs_nmea_decode(&s, cfg, r);
}

static void test_hdt_from_any_talker(void)
{
    ahrs_nmea_config cfg = AHRS_NMEA_DEFAULTS;
    ahrs_nmea_reading r;
    CHECK(decode("HEHDT,274.07,T", &cfg, &r) == AHRS_NMEA_OK);
    CHECK(r.has_heading && !r.has_attitude && !r.has_time);
    CHECK_NEAR(r.heading_rad, 274.07 * DEG, 1e-12);
    CHECK(decode("HCHDT,0.0,T", &cfg, &r) == AHRS_NMEA_OK && r.heading_rad == 0.0);
    CHECK(decode("HCHDT,360.0,T", &cfg, &r) == AHRS_NMEA_OK && r.heading_rad < 1e-12); /* wraps to 0 */
    cfg.heading_offset_deg = -1.5;
    CHECK(decode("GPHDT,0.5,T", &cfg, &r) == AHRS_NMEA_OK);
    CHECK_NEAR(r.heading_rad, 359.0 * DEG, 1e-12);
    cfg = AHRS_NMEA_DEFAULTS;
    CHECK(decode("HEHDT,274.07,M", &cfg, &r) == AHRS_NMEA_NOT_TRUE);
    CHECK(decode("HEHDT,274.07", &cfg, &r) == AHRS_NMEA_NOT_TRUE);
    CHECK(decode("HEHDT,,T", &cfg, &r) == AHRS_NMEA_MISSING_FIELD);
    CHECK(decode("HEHDT,361,T", &cfg, &r) == AHRS_NMEA_HEADING_RANGE);
    CHECK(decode("HEHDT,-1,T", &cfg, &r) == AHRS_NMEA_HEADING_RANGE);
    CHECK(decode("HEHDT,2e2,T", &cfg, &r) == AHRS_NMEA_BAD_FIELD);
    CHECK(decode("GPGGA,1,2", &cfg, &r) == AHRS_NMEA_NOT_MINE);
}

static void test_pashr(void)
{
    ahrs_nmea_config cfg = AHRS_NMEA_DEFAULTS;
    ahrs_nmea_reading r;
    /* the published example form, with the IMU status field */
    CHECK(decode("PASHR,163029.000,158.09,T,-0.30,+0.31,+0.01,0.029,0.029,0.059,1,1", &cfg, &r) == AHRS_NMEA_OK);
    CHECK(r.has_heading && r.has_attitude && r.has_time && r.has_accuracy && r.has_heave);
    CHECK_NEAR(r.time_of_day_s, 16 * 3600 + 30 * 60 + 29.0, 1e-9);
    CHECK_NEAR(r.heading_rad, 158.09 * DEG, 1e-12);
    CHECK_NEAR(r.roll_rad, -0.30 * DEG, 1e-12);
    CHECK_NEAR(r.pitch_rad, 0.31 * DEG, 1e-12);
    CHECK_NEAR(r.heave_m, 0.01, 1e-12);
    CHECK_NEAR(r.heading_sigma_rad, 0.059 * DEG, 1e-12);
    CHECK(r.gnss_quality == 1 && r.imu_status == 1);
    /* older firmware: no IMU status; a receiver that leaves heave empty */
    CHECK(decode("PASHR,163029.000,158.09,T,-0.30,+0.31,,0.029,0.029,0.059,2", &cfg, &r) == AHRS_NMEA_OK);
    CHECK(r.imu_status == -1 && r.gnss_quality == 2 && !r.has_heave);
    /* a device with the other signs, configured */
    cfg.roll_sign = cfg.pitch_sign = -1;
    CHECK(decode("PASHR,163029.000,158.09,T,-0.30,+0.31,+0.01,0.029,0.029,0.059,1,1", &cfg, &r) == AHRS_NMEA_OK);
    CHECK_NEAR(r.roll_rad, 0.30 * DEG, 1e-12);
    CHECK_NEAR(r.pitch_rad, -0.31 * DEG, 1e-12);
}

static void test_pashr_refusals(void)
{
    ahrs_nmea_config cfg = AHRS_NMEA_DEFAULTS;
    ahrs_nmea_reading r;
    CHECK(decode("PASHR,163029.000,158.09,T,-0.30", &cfg, &r) == AHRS_NMEA_MISSING_FIELD);
    CHECK(decode("PASHR,256029.000,158.09,T,0,0,0,0.1,0.1,0.1,1,1", &cfg, &r) == AHRS_NMEA_TIME_RANGE);
    CHECK(decode("PASHR,163029.000,158.09,M,0,0,0,0.1,0.1,0.1,1,1", &cfg, &r) == AHRS_NMEA_NOT_TRUE);
    CHECK(decode("PASHR,163029.000,158.09,T,181,0,0,0.1,0.1,0.1,1,1", &cfg, &r) == AHRS_NMEA_ATTITUDE_RANGE);
    CHECK(decode("PASHR,163029.000,158.09,T,0,-90.5,0,0.1,0.1,0.1,1,1", &cfg, &r) == AHRS_NMEA_ATTITUDE_RANGE);
    CHECK(decode("PASHR,163029.000,158.09,T,0,0,0,-0.1,0.1,0.1,1,1", &cfg, &r) == AHRS_NMEA_ACCURACY_RANGE);
    CHECK(decode("PASHR,163029.000,158.09,T,0,0,0,0.1,0.1,0.1,7,1", &cfg, &r) == AHRS_NMEA_STATUS_RANGE);
    CHECK(decode("PASHR,163029.000,158.09,T,0,0,0,0.1,0.1,0.1,1,5", &cfg, &r) == AHRS_NMEA_STATUS_RANGE);
    CHECK(decode("PASHR,163029.000,158.09,T,0,0,xx,0.1,0.1,0.1,1,1", &cfg, &r) == AHRS_NMEA_BAD_FIELD);
    CHECK(decode("PASHR,163029.000,158.09,T,0,nan,0,0.1,0.1,0.1,1,1", &cfg, &r) == AHRS_NMEA_BAD_FIELD);
    /* a refused sentence leaves nothing behind that looks decoded */
    CHECK(!r.has_attitude || r.roll_rad == 0.0);
}

static const unit_test tests[] = {
    {"ahrs_hdt_from_any_talker", test_hdt_from_any_talker},
    {"ahrs_pashr", test_pashr},
    {"ahrs_pashr_refusals", test_pashr_refusals},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
