#include "common/crc32.h"

/* Bitwise, a byte at a time: the radio's frames are kilobytes at radio
 * rates, so a table would buy nothing worth its 1 KiB. */
uint32_t crc32_update(uint32_t crc, const void *data, size_t n)
{
    const uint8_t *p = data;
    crc = ~crc;
    for (size_t i = 0; i < n; i++) {
        crc ^= p[i];
        for (int k = 0; k < 8; k++)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}
