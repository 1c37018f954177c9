/* SHA-256 (FIPS 180-4), for checking plugin uploads against their digest
 * before anything is written to disk or loaded. Self-contained: no OpenSSL
 * or GLib headers are needed on the build machine. */
#ifndef AUV_SHA256_H
#define AUV_SHA256_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
    uint32_t h[8];
    uint64_t bytes;
    uint8_t block[64];
    size_t used;
} sha256_ctx;

void sha256_init(sha256_ctx *c);
void sha256_update(sha256_ctx *c, const void *data, size_t len);
void sha256_final(sha256_ctx *c, uint8_t digest[32]);
/* Digest of one buffer as 64 lowercase hex characters + NUL. */
void sha256_hex(const void *data, size_t len, char hex[65]);

#endif
