/* Unit tests of the heading and attitude sentences (c/drivers/ahrs/ahrs_nmea.c):
 * HDT from any talker, PASHR with and without its last field, RDI's PRDID, VectorNav's VNYMR
 * (the manual's register-27 example as the async sentence), the signs and
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
    /* a gyro still settling says "no heading" with an empty field: valid, no value */
    CHECK(decode("HEHDT,,T", &cfg, &r) == AHRS_NMEA_OK && !r.has_heading);
    CHECK(decode("HEHDT", &cfg, &r) == AHRS_NMEA_MISSING_FIELD);
    CHECK(decode("HEHDT,361,T", &cfg, &r) == AHRS_NMEA_HEADING_RANGE);
    CHECK(decode("HEHDT,-1,T", &cfg, &r) == AHRS_NMEA_HEADING_RANGE);
    CHECK(decode("HEHDT,2e2,T", &cfg, &r) == AHRS_NMEA_BAD_FIELD);
    CHECK(decode("GPGGA,1,2", &cfg, &r) == AHRS_NMEA_NOT_MINE);
}

/* THS (NMEA 3.0 on): heading and mode; V (not valid) or empty is no value */
static void test_ths(void)
{
    ahrs_nmea_config cfg = AHRS_NMEA_DEFAULTS;
    ahrs_nmea_reading r;
    CHECK(decode("HETHS,274.07,A", &cfg, &r) == AHRS_NMEA_OK && r.has_heading);
    CHECK_NEAR(r.heading_rad, 274.07 * DEG, 1e-12);
    CHECK(decode("INTHS,12.5,E", &cfg, &r) == AHRS_NMEA_OK && r.has_heading);
    CHECK(decode("HETHS,274.07,V", &cfg, &r) == AHRS_NMEA_OK && !r.has_heading);
    CHECK(decode("HETHS,,V", &cfg, &r) == AHRS_NMEA_OK && !r.has_heading);
    CHECK(decode("HETHS,274.07,Q", &cfg, &r) == AHRS_NMEA_STATUS_RANGE);
    CHECK(decode("HETHS,400,A", &cfg, &r) == AHRS_NMEA_HEADING_RANGE);
    CHECK(decode("HETHS,274.07", &cfg, &r) == AHRS_NMEA_MISSING_FIELD);
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
    /* Ashtech's own $PASHR family (a name first, not a time) is not ours */
    CHECK(decode("PASHR,POS,0,03,183530.00,2037.76012,N,08704.07373,W,058.48,,000.0,000.0,-000.0,04.1,02.0,03.5,"
                 "01.8,GA10",
                 &cfg, &r) == AHRS_NMEA_NOT_MINE);
    CHECK(decode("PASHR,ATT,183530.0,158.09,-0.30,+0.31,0.0021,0.0054,0", &cfg, &r) == AHRS_NMEA_NOT_MINE);
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

/* VectorNav's published register-27 example (VN-100 User Manual UM001, 7.2.3,
 * "$VNRRG,27,...*4F"), as its asynchronous $VNYMR output: the same 12 fields. */
#define VNYMR_EXAMPLE "VNYMR,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,-0.001222,-0.000450,-0.001218"

/* RDI's $PRDID (pitch, roll, heading), as an Octans or a Workhorse's
 * external-sensor input writes it, and its refusals. */
static void test_prdid(void)
{
    ahrs_nmea_config cfg = AHRS_NMEA_DEFAULTS;
    ahrs_nmea_reading r;
    CHECK(decode("PRDID,-1.31,7.81,47.31", &cfg, &r) == AHRS_NMEA_OK);
    CHECK(r.has_heading && r.has_attitude && !r.has_time && !r.has_rates && !r.has_accuracy);
    CHECK_NEAR(r.pitch_rad, -1.31 * DEG, 1e-12);
    CHECK_NEAR(r.roll_rad, 7.81 * DEG, 1e-12);
    CHECK_NEAR(r.heading_rad, 47.31 * DEG, 1e-12);
    /* signs and the mounting's offset, as for the other sentences */
    cfg.roll_sign = -1;
    cfg.heading_offset_deg = 20.0;
    CHECK(decode("PRDID,+002.50,-003.00,350.00", &cfg, &r) == AHRS_NMEA_OK);
    CHECK_NEAR(r.roll_rad, 3.0 * DEG, 1e-12);
    CHECK_NEAR(r.pitch_rad, 2.5 * DEG, 1e-12);
    CHECK_NEAR(r.heading_rad, 10.0 * DEG, 1e-9);
    cfg = AHRS_NMEA_DEFAULTS;
    CHECK(decode("PRDID,1.0,2.0", &cfg, &r) == AHRS_NMEA_MISSING_FIELD);
    CHECK(decode("PRDID,1.0,2.0,3.0,4.0", &cfg, &r) == AHRS_NMEA_BAD_FIELD);
    CHECK(decode("PRDID,1.0,,3.0", &cfg, &r) == AHRS_NMEA_MISSING_FIELD);
    CHECK(decode("PRDID,1.0,x,3.0", &cfg, &r) == AHRS_NMEA_BAD_FIELD);
    CHECK(decode("PRDID,91.0,0,3.0", &cfg, &r) == AHRS_NMEA_ATTITUDE_RANGE);
    CHECK(decode("PRDID,0,-180.5,3.0", &cfg, &r) == AHRS_NMEA_ATTITUDE_RANGE);
    CHECK(decode("PRDID,0,0,360.5", &cfg, &r) == AHRS_NMEA_HEADING_RANGE);
    CHECK(decode("PRDID,0,0,-1", &cfg, &r) == AHRS_NMEA_HEADING_RANGE);
}

static void test_vnymr(void)
{
    ahrs_nmea_config cfg = AHRS_NMEA_DEFAULTS;
    ahrs_nmea_reading r;
    /* the checksum rule is NMEA's: the manual's own example line checks */
    const char *rrg = "$VNRRG,27,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,"
                      "-0.001222,-0.000450,-0.001218*4F";
    nmea_sentence s;
    CHECK(nmea_parse_line(rrg, strlen(rrg), 0, &s) == NMEA_OK);
    CHECK(ahrs_nmea_decode(&s, &cfg, &r) == AHRS_NMEA_NOT_MINE); /* a register read: not an output */

    CHECK(decode(VNYMR_EXAMPLE, &cfg, &r) == AHRS_NMEA_OK);
    CHECK(r.has_heading && r.has_attitude && r.has_rates && r.has_imu && !r.has_time && !r.has_accuracy);
    CHECK_NEAR(r.heading_rad, 6.380 * DEG, 1e-12);
    CHECK_NEAR(r.pitch_rad, 0.023 * DEG, 1e-12);
    CHECK_NEAR(r.roll_rad, -1.953 * DEG, 1e-12);
    CHECK_NEAR(r.mag_gauss[0], 1.0640, 1e-12);
    CHECK_NEAR(r.mag_gauss[2], 3.0614, 1e-12);
    CHECK_NEAR(r.accel_mps2[2], -9.758, 1e-12);
    CHECK_NEAR(r.p_radps, -0.001222, 1e-12);
    CHECK_NEAR(r.q_radps, -0.000450, 1e-12);
    CHECK_NEAR(r.r_radps, -0.001218, 1e-12);

    /* yaw in -180..180 is a heading in [0, 2 pi); the offset adds to it */
    CHECK(decode("VNYMR,-010.000,+000.000,+000.000,+0.2,+0.0,+0.4,+00.000,+00.000,-09.807,+0.1,+0.2,+0.3", &cfg, &r) ==
          AHRS_NMEA_OK);
    CHECK_NEAR(r.heading_rad, 350.0 * DEG, 1e-12);
    CHECK(decode("VNYMR,+180.000,+000.000,+000.000,+0.2,+0.0,+0.4,+00.000,+00.000,-09.807,0,0,0", &cfg, &r) ==
          AHRS_NMEA_OK);
    CHECK_NEAR(r.heading_rad, 180.0 * DEG, 1e-12);
    cfg.heading_offset_deg = 15.0;
    CHECK(decode("VNYMR,-010.000,+000.000,+000.000,+0.2,+0.0,+0.4,+00.000,+00.000,-09.807,+0.1,+0.2,+0.3", &cfg, &r) ==
          AHRS_NMEA_OK);
    CHECK_NEAR(r.heading_rad, 5.0 * DEG, 1e-12);
    CHECK_NEAR(r.r_radps, 0.3, 1e-12); /* the offset does not rotate the rates */

    /* the signs turn an axis's angle and its rate alike */
    cfg = AHRS_NMEA_DEFAULTS;
    cfg.roll_sign = cfg.pitch_sign = -1;
    CHECK(decode(VNYMR_EXAMPLE, &cfg, &r) == AHRS_NMEA_OK);
    CHECK_NEAR(r.roll_rad, 1.953 * DEG, 1e-12);
    CHECK_NEAR(r.pitch_rad, -0.023 * DEG, 1e-12);
    CHECK_NEAR(r.p_radps, 0.001222, 1e-12);
    CHECK_NEAR(r.q_radps, 0.000450, 1e-12);
    CHECK_NEAR(r.r_radps, -0.001218, 1e-12);
}

static void test_vnymr_refusals(void)
{
    ahrs_nmea_config cfg = AHRS_NMEA_DEFAULTS;
    ahrs_nmea_reading r;
    const char *cases[][2] = {
        {"VNYMR,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,-0.001222,-0.000450",
         "missing field"},
        {"VNYMR,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,-0.001222,-0.000450,",
         "missing field"}, /* the last field empty */
        {"VNYMR,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,-0.001222,-0.000450,"
         "-0.001218,0",
         "malformed field"}, /* a 13th field */
        {"VNYMR,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,-0.001222,1e3,-0.001218",
         "malformed field"},
        {"VNYMR,+186.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,0,0,0",
         "heading out of range"},
        {"VNYMR,+006.380,+090.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,0,0,0",
         "attitude out of range"},
        {"VNYMR,+006.380,+000.023,-181.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,0,0,0",
         "attitude out of range"},
        {"VNYMR,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,0,0,-41.0",
         "rate out of range"},
        {"VNYMR,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+300.344,-09.758,0,0,0",
         "acceleration out of range"},
        {"VNYMR,+006.380,+000.023,-001.953,+1.0640,-20.2531,+3.0614,+00.005,+00.344,-09.758,0,0,0",
         "magnetic field out of range"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        ahrs_nmea_result res = decode(cases[i][0], &cfg, &r);
        if (strcmp(ahrs_nmea_result_name(res), cases[i][1]) != 0)
            UNIT_FAIL("%s: '%s', not '%s'", cases[i][0], ahrs_nmea_result_name(res), cases[i][1]);
    }
    /* another talker's YMR is not VectorNav's */
    CHECK(decode("GPYMR,+006.380,+000.023,-001.953,+1.0640,-0.2531,+3.0614,+00.005,+00.344,-09.758,0,0,0", &cfg, &r) ==
          AHRS_NMEA_NOT_MINE);
}

static const unit_test tests[] = {
    {"ahrs_hdt_from_any_talker", test_hdt_from_any_talker},
    {"ahrs_ths", test_ths},
    {"ahrs_pashr", test_pashr},
    {"ahrs_pashr_refusals", test_pashr_refusals},
    {"ahrs_prdid", test_prdid},
    {"ahrs_vnymr", test_vnymr},
    {"ahrs_vnymr_refusals", test_vnymr_refusals},
    {NULL, NULL},
};

__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
