#include "common/auth_acoustic.h"

#include <string.h>

#include "common/auth_mac.h"

#define ACOUSTIC_LABEL "CHASM-ACOUSTIC-1"

int auth_acoustic_tag(const uint8_t *key, size_t key_len, const void *payload, size_t len, uint32_t counter24,
                      uint32_t *tag)
{
    const size_t label = strlen(ACOUSTIC_LABEL);
    uint8_t msg[sizeof ACOUSTIC_LABEL + 3 + AUTH_ACOUSTIC_MAX_PAYLOAD];
    uint8_t mac[AUTH_MAC_BYTES];
    if (len > AUTH_ACOUSTIC_MAX_PAYLOAD)
        return -1;
    memcpy(msg, ACOUSTIC_LABEL, label);
    msg[label] = (uint8_t)(counter24 >> 16);
    msg[label + 1] = (uint8_t)(counter24 >> 8);
    msg[label + 2] = (uint8_t)counter24;
    if (len)
        memcpy(msg + label + 3, payload, len);
    if (auth_hmac_sha256(key, key_len, msg, label + 3 + len, mac))
        return -1;
    *tag = (uint32_t)mac[0] << 24 | (uint32_t)mac[1] << 16 | (uint32_t)mac[2] << 8 | mac[3];
    return 0;
}

void auth_acoustic_init(auth_acoustic_window *w)
{
    w->newest = -1;
    w->seen = 0;
}

int auth_acoustic_verify(auth_acoustic_window *w, const uint8_t *key, size_t key_len, const void *payload,
                         size_t len, uint32_t counter24, uint32_t tag)
{
    uint32_t want;
    uint8_t a[4], b[4];
    if (counter24 > 0xFFFFFF || auth_acoustic_tag(key, key_len, payload, len, counter24, &want))
        return 1;
    for (int i = 0; i < 4; i++) {
        a[i] = (uint8_t)(want >> (24 - 8 * i));
        b[i] = (uint8_t)(tag >> (24 - 8 * i));
    }
    if (!auth_mac_equal(a, b, 4))
        return 1;
    if ((int64_t)counter24 > w->newest) {
        int64_t shift = (int64_t)counter24 - w->newest;
        w->seen = shift < AUTH_ACOUSTIC_WINDOW ? (w->seen << shift) | 1u : 1u;
        w->newest = counter24;
        return 0;
    }
    int64_t back = w->newest - (int64_t)counter24;
    if (back >= AUTH_ACOUSTIC_WINDOW)
        return 3;
    if (w->seen >> back & 1u)
        return 2;
    w->seen |= 1u << back;
    return 0;
}
