/* The Maestro fuzz target's one input, shared with the corpus test
 * (tests/drivers/test_maestro.c): which replies it gave, which it refused. */
#ifndef DRIVERS_FUZZ_MAESTRO_H
#define DRIVERS_FUZZ_MAESTRO_H

#include <stddef.h>
#include <stdint.h>

#include "drivers/servo/maestro.h"

/* An input is either a channel table (it starts with "TABLE\n"; the rest is
 * the file), or a reply stream: byte 0 the number of queries sent (mod 65),
 * then one byte per query (bits 7-6: 0 position, 1 errors, 2 moving state,
 * 3 a deadline passing before the device's bytes; bits 5-0 the channel),
 * then the device's bytes; the reply deadline passes at the end. Aborts when
 * a byte is neither in an accepted reply nor counted as refused. Returns the
 * decoder's final state in *rx (may be NULL), and for a table 0 when read,
 * -1 when refused. */
int maestro_fuzz_one(const uint8_t *data, size_t size, maestro_rx *rx);

#endif
