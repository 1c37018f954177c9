/* CRC-32 as zlib, Python's zlib.crc32 and Ethernet compute it (reflected
 * polynomial 0xEDB88320, initial and final XOR 0xFFFFFFFF): the check of
 * the radio's byte-pipe frames (docs/radio.md, "The byte pipe"), which the
 * Python gateways compute with zlib.crc32. */
#ifndef AUV_CRC32_H
#define AUV_CRC32_H

#include <stddef.h>
#include <stdint.h>

/* The CRC-32 of data[0..n); crc32_update(0, ...) starts one, and feeding a
 * buffer in pieces gives the CRC of the whole. */
uint32_t crc32_update(uint32_t crc, const void *data, size_t n);

#endif
