/* Fuzz entry point: any bytes through the NMEA framer, every sentence it passes
 * through the heading/attitude decoder and the field parsers (libFuzzer, or the
 * project's driver c/chasm/fuzz/fuzz_driver.c where clang is missing). */
#include <stddef.h>
#include <stdint.h>

#include "drivers/ahrs/ahrs_nmea.h"
#include "drivers/common/nmea.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    nmea_framer f;
    nmea_framer_init(&f, size > 0 && (data[0] & 1));
    nmea_sentence s;
    ahrs_nmea_config cfg = AHRS_NMEA_DEFAULTS;
    for (size_t i = 0; i < size; i++) {
        if (nmea_framer_push(&f, data[i], &s) != NMEA_OK)
            continue;
        ahrs_nmea_reading r;
        (void)ahrs_nmea_decode(&s, &cfg, &r);
        double d, t;
        long l;
        int64_t day;
        for (int k = 0; k < s.nfields + 1; k++) {
            (void)nmea_field_double(&s, k, &d);
            (void)nmea_field_int(&s, k, &l);
            (void)nmea_field_latitude(&s, k, &d);
            (void)nmea_field_longitude(&s, k, &d);
            (void)nmea_field_time_of_day(&s, k, &t);
            (void)nmea_field_date_ddmmyy(&s, k, &day);
        }
    }
    return 0;
}
