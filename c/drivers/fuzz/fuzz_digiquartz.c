/* Fuzz entry point: any bytes through the Digiquartz answer framer, and every
 * answer through the unit and depth conversions. */
#include <stddef.h>
#include <stdint.h>

#include "drivers/pressure/digiquartz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    dq_framer f;
    dq_framer_init(&f);
    dq_depth_model m = DQ_DEPTH_DEFAULTS;
    for (size_t i = 0; i < size; i++) {
        dq_answer a;
        if (dq_framer_push(&f, data[i], 0, 1, &a) != DQ_OK)
            continue;
        double pa, c;
        for (int unit = 0; unit <= 9; unit++)
            if (dq_pressure_pa(a.value, unit, &pa) == DQ_OK)
                (void)dq_depth_m(&m, pa);
        (void)dq_temperature_c(a.value, &c);
    }
    return 0;
}
