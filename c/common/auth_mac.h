/* The cryptography of command authentication (docs/security.md), all of it
 * OpenSSL's libcrypto: SHA-256 (plugin digests), HMAC-SHA-256 (command
 * MACs; the acoustic link's tag is auth_acoustic.h). Nothing here is a
 * hand-written primitive: only the framing around libcrypto's. */
#ifndef AUV_AUTH_MAC_H
#define AUV_AUTH_MAC_H

#include <stddef.h>
#include <stdint.h>

#define AUTH_MAC_BYTES 32

/* Digest of one buffer as 64 lowercase hex characters + NUL. */
void auth_sha256_hex(const void *data, size_t len, char hex[65]);

/* HMAC-SHA-256(key, data). 0, or -1 when libcrypto fails (out contains zeros). */
int auth_hmac_sha256(const uint8_t *key, size_t key_len, const void *data, size_t len, uint8_t out[AUTH_MAC_BYTES]);

/* Equal without a time that depends on where they differ (CRYPTO_memcmp). */
int auth_mac_equal(const uint8_t *a, const uint8_t *b, size_t n);

#endif
