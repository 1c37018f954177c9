/* Unit tests of the NMEA framing and fields (c/drivers/common/nmea.c): the
 * published sentence format, and every way a stream can be wrong. */
#include <math.h>
#include <string.h>

#include "drivers/common/nmea.h"
#include "../harness/unit.h"

static nmea_result parse(const char *line, nmea_sentence *s) { return nmea_parse_line(line, strlen(line), 0, s); }

/* Feeds a whole string; returns the number of sentences and counts refusals. */
static int feed(nmea_framer *f, const char *bytes, size_t n, int refused[NMEA_RESULT_COUNT], nmea_sentence *last)
{
    int ok = 0;
    for (size_t i = 0; i < n; i++) {
        int r = nmea_framer_push(f, (uint8_t)bytes[i], last);
        if (r == NMEA_OK)
            ok++;
        else if (r > 0)
            refused[r]++;
    }
    return ok;
}

static void test_checksum_and_split(void)
{
    nmea_sentence s;
    /* a published GGA example with its checksum */
    CHECK(parse("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n", &s) == NMEA_OK);
    CHECK_STR(s.talker, "GP");
    CHECK_STR(s.type, "GGA");
    CHECK(s.nfields == 14);
    CHECK_STR(s.field[0], "123519");
    CHECK_STR(s.field[13], "");
    CHECK(parse("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*48", &s) == NMEA_BAD_CHECKSUM);
    CHECK(parse("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,", &s) == NMEA_NO_CHECKSUM);
    CHECK(nmea_parse_line("$GPGGA,1,2", 10, 1, &s) == NMEA_OK && s.nfields == 2);
    CHECK(parse("$GPGGA,1*2,3*00", &s) == NMEA_BAD_CHECKSUM);
    char line[64], addr[64];
    nmea_format(addr, sizeof addr, "GP,1");
    CHECK(parse(addr, &s) == NMEA_BAD_ADDRESS);
    nmea_format(addr, sizeof addr, "gpgga,1");
    CHECK(parse(addr, &s) == NMEA_BAD_ADDRESS);
    char body[] = "PASHR,123519.00,45.12,T,1.20,-0.40,0.10,0.05,0.05,0.10,1,0";
    CHECK(nmea_format(line, sizeof line, body) == -1); /* does not fit */
    char big[128];
    int n = nmea_format(big, sizeof big, body);
    CHECK(n > 0 && big[n - 2] == '\r' && big[n - 1] == '\n');
    CHECK(parse(big, &s) == NMEA_OK);
    CHECK_STR(s.talker, "");
    CHECK_STR(s.type, "PASHR");
    CHECK(s.nfields == 11);
}

static void test_framer_survives_any_stream(void)
{
    nmea_framer f;
    nmea_framer_init(&f, 0);
    nmea_sentence s;
    int refused[NMEA_RESULT_COUNT] = {0};
    char good[128];
    nmea_format(good, sizeof good, "HEHDT,123.4,T");
    /* garbage, a good one, a cut one followed by a good one, binary junk inside one */
    char stream[1024];
    int len = snprintf(stream, sizeof stream, "xx\x01\xff%s$HEHDT,12%s$HEHDT,1\x02" "3,T*00\r\n%s", good, good, good);
    CHECK(feed(&f, stream, (size_t)len, refused, &s) == 3);
    CHECK(refused[NMEA_TRUNCATED] == 1 && refused[NMEA_BAD_CHAR] == 1);
    CHECK(f.garbage_bytes == 4);
    CHECK_STR(s.type, "HDT");
    /* an endless line: refused once, and the next sentence still comes through */
    nmea_framer_init(&f, 0);
    memset(refused, 0, sizeof refused);
    char endless[2000];
    endless[0] = '$';
    memset(endless + 1, 'A', sizeof endless - 1);
    CHECK(feed(&f, endless, sizeof endless, refused, &s) == 0);
    CHECK(refused[NMEA_TOO_LONG] == 1);
    CHECK(feed(&f, "\r\n", 2, refused, &s) == 0);
    CHECK(feed(&f, good, strlen(good), refused, &s) == 1);
}

static void test_fields(void)
{
    nmea_sentence s;
    CHECK(parse("$GPRMC,225446.33,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E*59", &s) == NMEA_OK ||
          parse("$GPRMC,225446.33,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E", &s) == NMEA_NO_CHECKSUM);
    char line[128];
    nmea_format(line, sizeof line, "GPRMC,225446.33,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E");
    CHECK(parse(line, &s) == NMEA_OK);
    double t, lat, lon, d;
    int64_t day;
    CHECK(nmea_field_time_of_day(&s, 0, &t) == 1);
    CHECK_NEAR(t, 22 * 3600 + 54 * 60 + 46.33, 1e-9);
    CHECK(nmea_field_latitude(&s, 2, &lat) == 1);
    CHECK_NEAR(lat, 49 + 16.45 / 60, 1e-12);
    CHECK(nmea_field_longitude(&s, 4, &lon) == 1);
    CHECK_NEAR(lon, -(123 + 11.12 / 60), 1e-12);
    CHECK(nmea_field_date_ddmmyy(&s, 8, &day) == 1);
    CHECK(day == nmea_unix_day(1994, 11, 19));
    CHECK(nmea_unix_day(1970, 1, 1) == 0 && nmea_unix_day(2000, 3, 1) == 11017);
    CHECK(nmea_unix_day(2023, 2, 29) == -1 && nmea_unix_day(2024, 2, 29) > 0);
    /* absurd values are refused, empty ones are "no value" */
    nmea_format(line, sizeof line, "GPRMC,256060,A,9516.45,N,12311.12,Q,x,,321394,,");
    CHECK(parse(line, &s) == NMEA_OK);
    CHECK(nmea_field_time_of_day(&s, 0, &t) == -1);
    CHECK(nmea_field_latitude(&s, 2, &lat) == -1);
    CHECK(nmea_field_longitude(&s, 4, &lon) == -1);
    CHECK(nmea_field_double(&s, 6, &d) == -1);
    CHECK(nmea_field_double(&s, 7, &d) == 0);
    CHECK(nmea_field_date_ddmmyy(&s, 8, &day) == -1);
    nmea_format(line, sizeof line, "GPGGA,000000,8960.0,N,18000.001,E,1,nan,1e3,0x10");
    CHECK(parse(line, &s) == NMEA_OK);
    CHECK(nmea_field_latitude(&s, 1, &lat) == -1);  /* 60 minutes */
    CHECK(nmea_field_longitude(&s, 3, &lon) == -1); /* past 180 */
    CHECK(nmea_field_double(&s, 6, &d) == -1 && nmea_field_double(&s, 7, &d) == -1);
    CHECK(nmea_field_double(&s, 8, &d) == -1);
    CHECK(nmea_field_double(&s, 20, &d) == 0); /* past the last field: empty */
}

/* What real receivers send that the standard allows or that leaves no
 * doubt (gpsd's recordings of dozens of receivers show each). */
static void test_real_receivers_framing(void)
{
    nmea_framer f;
    nmea_sentence s;
    int refused[NMEA_RESULT_COUNT] = {0};
    char a[128], b[128], stream[512];
    nmea_format(a, sizeof a, "GPGSA,A,1,,,,,,,,,,,,,,,");
    nmea_format(b, sizeof b, "GPRMC,235949.00,V,0000.0000,N,00000.0000,E,,,220899,,,N");
    /* a full output buffer drops the CR LF: "...*1E$GPRMC,...": both are whole */
    int len = snprintf(stream, sizeof stream, "%.*s%s", (int)strlen(a) - 2, a, b);
    nmea_framer_init(&f, 0);
    CHECK(feed(&f, stream, (size_t)len, refused, &s) == 2);
    CHECK_STR(s.type, "RMC");
    for (int k = 1; k < NMEA_RESULT_COUNT; k++)
        CHECK(refused[k] == 0);
    /* the same with one checksum digit lost: cut, not whole */
    len = snprintf(stream, sizeof stream, "%.*s%s", (int)strlen(a) - 3, a, b);
    nmea_framer_init(&f, 0);
    CHECK(feed(&f, stream, (size_t)len, refused, &s) == 1 && refused[NMEA_TRUNCATED] == 1);
    /* a line ended by LF alone, by CR alone; a lower-case checksum */
    memset(refused, 0, sizeof refused);
    nmea_framer_init(&f, 0);
    const char *ends = "$GPRMC,205150.00,V,,,,,,,,,,,V*4a\n$GPRMC,205150.00,V,,,,,,,,,,,V*4A\r"
                       "$GPRMC,205150.00,V,,,,,,,,,,,V*4a\r\n";
    CHECK(feed(&f, ends, strlen(ends), refused, &s) == 3);
    CHECK(refused[NMEA_BAD_CHECKSUM] == 0 && s.checksummed == 1 && s.nfields == 13);
    /* no checksum: refused, or accepted and marked where the framer allows it */
    CHECK(parse("$GPZDA,222449,25,10,2010,+00,00\r\n", &s) == NMEA_NO_CHECKSUM);
    CHECK(nmea_parse_line("$GPZDA,222449,25,10,2010,+00,00", 31, 1, &s) == NMEA_OK && s.checksummed == 0);
    CHECK(nmea_parse_line(a, strlen(a), 1, &s) == NMEA_OK && s.checksummed == 1);
    CHECK(nmea_parse_line("$GPZDA,222449,25,10,2010,+00,00*1", 33, 1, &s) == NMEA_BAD_CHECKSUM);
    /* a u-blox's binary UBX frames between its sentences, a '$' inside them:
     * garbage, not a sentence with a bad character */
    memset(refused, 0, sizeof refused);
    nmea_framer_init(&f, 0);
    const char ubx[] = "\xb5\x62\x01\x07\x5c\x00$\x01\x02$G\x00\xff";
    CHECK(feed(&f, ubx, sizeof ubx - 1, refused, &s) == 0);
    CHECK(refused[NMEA_BAD_CHAR] == 0 && f.garbage_bytes == sizeof ubx - 1);
    CHECK(feed(&f, a, strlen(a), refused, &s) == 1);
}

static const unit_test tests[] = {
    {"checksum_and_split", test_checksum_and_split},
    {"real_receivers_framing", test_real_receivers_framing},
    {"framer_survives_any_stream", test_framer_survives_any_stream},
    {"fields", test_fields},
    {NULL, NULL},
};

/* Each test file of tests/drivers registers its list itself, so a new parser's
 * tests are one new file (main.c runs them all). */
__attribute__((constructor)) static void register_tests(void) { unit_register_list(tests); }
