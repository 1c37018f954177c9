/* libFuzzer entry point of the Maestro's reply decoder and channel-table
 * reader (make fuzz); without clang, c/chasm/fuzz/fuzz_driver.c
 * drives it. The input format is in fuzz_maestro.h. */
#include "drivers/fuzz/fuzz_maestro.h"

#include <stdlib.h>
#include <string.h>

#include "drivers/servo/actuator_map.h"

static int table(const uint8_t *data, size_t size)
{
    am_config cfg;
    char err[512];
    if (am_config_parse(&cfg, (const char *)data, size, "fuzz", err, sizeof err)) {
        if (strncmp(err, "fuzz:", 5)) /* every refusal says where */
            abort();
        return -1;
    }
    /* a table read is a table every command maps within its limits */
    am_state st;
    am_state_init(&st);
    uint16_t t[MAESTRO_MAX_CHANNELS];
    am_command c = {0, 1e300, -1e300, 1e9};
    if (am_apply(&cfg, &st, &c, 0, t) != AM_OK)
        abort();
    for (unsigned i = 0; i < cfg.n; i++)
        if (t[i] < 4 || t[i] > MAESTRO_MAX_TARGET || t[i] < cfg.ch[i].min_us * 4 - 0.5 || t[i] > cfg.ch[i].max_us * 4 + 0.5)
            abort();
    return 0;
}

int maestro_fuzz_one(const uint8_t *data, size_t size, maestro_rx *out)
{
    if (size >= 6 && !memcmp(data, "TABLE\n", 6))
        return table(data + 6, size - 6);
    maestro_rx rx;
    maestro_rx_init(&rx);
    size_t i = 0, accepted = 0, pushed = 0;
    unsigned k = size ? data[i++] % 65 : 0;
    for (; k && i < size; k--, i++) {
        unsigned q = data[i] >> 6;
        if (q == 3)
            maestro_rx_timeout(&rx);
        else
            maestro_rx_expect(&rx, (maestro_query)q, data[i] & 0x3F);
    }
    for (; i < size; i++, pushed++) {
        maestro_rx_event ev;
        maestro_rx_result r = maestro_rx_push(&rx, data[i], &ev);
        if (r != ev.kind || (r == MRX_MOVING && ev.value > 1) || (r == MRX_POSITION && ev.value > MAESTRO_MAX_TARGET))
            abort();
        accepted += r == MRX_MOVING ? 1 : r == MRX_POSITION || r == MRX_ERRORS ? 2 : 0;
    }
    maestro_rx_timeout(&rx);
    if (accepted + rx.refused_bytes != pushed)
        abort();
    if (out)
        *out = rx;
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    maestro_fuzz_one(data, size, NULL);
    return 0;
}
