/* libFuzzer target of the PD0 framer and decoder (c/drivers/dvl): any bytes
 * as a stream, cut into reads at lengths taken from the input itself, every
 * ensemble decoded and turned into a dvl_t, and the whole input decoded as
 * one buffer too. Neither may read outside what it was given (ASan), and the
 * framer must end every input: a refusal always consumes a byte. */
#include <stdint.h>
#include <stdlib.h>

#include "auv/auv_dvl_t.h"
#include "drivers/dvl/pd0.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static pd0_framer framer;
static pd0_ensemble ens;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    pd0_mounting m;
    pd0_mounting_default(&m);
    auv_dvl_t out = {0};
    pd0_decode(data, size, &ens);
    pd0_framer_init(&framer);
    pd0_continuity cont = {0};
    size_t at = 0;
    unsigned cut = size ? data[0] : 1;
    while (at < size) {
        /* reads of 1..64 bytes, the lengths from the input's bytes */
        size_t n = 1 + (data[(at + cut) % size] & 63);
        if (n > size - at)
            n = size - at;
        const uint8_t *p = data + at, *e;
        size_t left = n, used, len;
        int r;
        unsigned spins = 0;
        while ((r = pd0_framer_push(&framer, p, left, &used, &e, &len)) != -1) {
            p += used;
            left -= used;
            if (++spins > 2 * (PD0_MAX_ENSEMBLE + 64))
                abort(); /* a framer that does not move on */
            if (r == PD0_OK && pd0_decode(e, len, &ens) == PD0_OK) {
                pd0_to_dvl(&ens, &m, &out);
                pd0_continuity_update(&cont, ens.ensemble_number, pd0_rtc_utime(&ens.rtc));
            }
        }
        at += n;
    }
    pd0_framer_flush(&framer);
    return 0;
}
