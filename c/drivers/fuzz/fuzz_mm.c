/* libFuzzer entry point of the Micro-Modem layer: any bytes through the NMEA
 * framer, the subset's parser and a bridge (with time passing), and every
 * message it accepts formatted back and parsed again, which must give the same
 * sentence: what the driver reads can never crash it, and what it writes the
 * parser takes. Built with libFuzzer (clang) or c/chasm/fuzz/fuzz_driver.c. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "drivers/modem/mm_bridge.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static mm_bridge b;
    static mm_out out;
    static nmea_framer f;
    static nmea_sentence s, again;
    mm_table t;
    mm_options o;
    const char *why;
    mm_options_default(&o);
    o.vehicle = "AUV1";
    o.ack = size > 0 && (data[0] & 1);
    if (mm_table_parse(&t, "AUV1=1,AUV2=2,AUV3=3", &why) || mm_bridge_init(&b, &o, &t, &why))
        abort();
    nmea_framer_init(&f, 0);
    int64_t now = 0;
    for (size_t i = 0; i < size; i++) {
        if (nmea_framer_push(&f, data[i], &s) != NMEA_OK)
            continue;
        mm_msg m, m2;
        if (mm_parse(&s, &m, &why) != 0)
            continue;
        char body[MM_BODY_MAX], line[NMEA_MAX_SENTENCE + 8];
        if (mm_format(&m, body, sizeof body) > 0) {
            /* what we write, we read back the same */
            if (nmea_format(line, sizeof line, body) < 0 || nmea_parse_line(line, strlen(line), 0, &again) != NMEA_OK ||
                mm_parse(&again, &m2, &why) != 0 || m2.kind != m.kind)
                abort();
        }
        mm_out_clear(&out);
        now += (int64_t)(data[i] % 7) * 1000000;
        mm_bridge_input(&b, &m, now, &out);
        mm_bridge_tick(&b, now, &out);
        if (m.kind == MM_CACYC) { /* a frame to send now and then */
            uint8_t p[40] = {0};
            mm_bridge_send(&b, (int32_t)i, (i & 1) ? "AUV2" : "", 2, p, 1 + (int)(i % 40), now, &out);
        }
    }
    return 0;
}
