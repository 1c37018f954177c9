#include "common/auth_mac.h"

#include <stdio.h>
#include <string.h>

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>

void auth_sha256_hex(const void *data, size_t len, char hex[65])
{
    uint8_t d[EVP_MAX_MD_SIZE];
    unsigned int n = 0;
    if (!EVP_Digest(data, len, d, &n, EVP_sha256(), NULL) || n != 32)
        memset(d, 0, 32); /* never matches a real digest: the upload is refused */
    for (int i = 0; i < 32; i++)
        snprintf(hex + 2 * i, 3, "%02x", d[i]);
}

int auth_hmac_sha256(const uint8_t *key, size_t key_len, const void *data, size_t len, uint8_t out[AUTH_MAC_BYTES])
{
    unsigned int n = 0;
    /* HMAC() reads no data pointer when len is 0, but wants a non-NULL one. */
    static const uint8_t none[1] = {0};
    if (!HMAC(EVP_sha256(), key, (int)key_len, len ? data : none, len, out, &n) || n != AUTH_MAC_BYTES) {
        memset(out, 0, AUTH_MAC_BYTES);
        return -1;
    }
    return 0;
}

int auth_mac_equal(const uint8_t *a, const uint8_t *b, size_t n) { return CRYPTO_memcmp(a, b, n) == 0; }
