#include "common/auth_commands.h"

#include <stdio.h>
#include <stdlib.h>

static auth_fields fields_of(const auv_command_auth_t *x)
{
    return (auth_fields){.key_id = x->key_id, .sender = x->sender, .counter = x->counter,
                         .mac = x->mac, .mac_len = x->mac_len};
}

/* One body for every command type (they differ only in their functions). */
#define VERIFY_ENCODED(TYPE, v, msg, now_us)                                   \
    do {                                                                       \
        static uint8_t no_mac[1];                                              \
        TYPE body = *(msg);                                                    \
        body.auth.mac_len = 0;                                                 \
        body.auth.mac = no_mac;                                                \
        int n = TYPE##_encoded_size(&body);                                    \
        uint8_t *buf = n > 0 ? malloc((size_t)n) : NULL;                       \
        auth_result r;                                                         \
        if (buf && TYPE##_encode(buf, 0, n, &body) == n) {                     \
            auth_fields f = fields_of(&(msg)->auth);                           \
            r = auth_verify((v), &f, buf, (size_t)n, (now_us));                \
        } else {                                                               \
            r = AUTH_BAD_MAC; /* not encodable: nothing could have signed it */ \
            (v)->refused[r]++;                                                 \
        }                                                                      \
        free(buf);                                                             \
        return r;                                                              \
    } while (0)

auth_result auth_verify_mission_command(auth_verifier *v, const auv_mission_command_t *c, int64_t now_us)
{
    VERIFY_ENCODED(auv_mission_command_t, v, c, now_us);
}

auth_result auth_verify_plugin_upload(auth_verifier *v, const auv_plugin_upload_t *u, int64_t now_us)
{
    VERIFY_ENCODED(auv_plugin_upload_t, v, u, now_us);
}

int auth_sign_mission_command(auv_mission_command_t *c, const auth_key *key, const char *sender, int64_t counter,
                              char sender_buf[AUTH_MAX_SENDER + 1], uint8_t mac[AUTH_MAC_BYTES])
{
    snprintf(sender_buf, AUTH_MAX_SENDER + 1, "%s", sender);
    c->auth.key_id = (char *)key->id;
    c->auth.sender = sender_buf;
    c->auth.counter = counter;
    c->auth.mac_len = 0;
    c->auth.mac = mac;
    int n = auv_mission_command_t_encoded_size(c);
    uint8_t *buf = n > 0 ? malloc((size_t)n) : NULL;
    int ok = buf && auv_mission_command_t_encode(buf, 0, n, c) == n &&
             auth_hmac_sha256(key->secret, key->len, buf, (size_t)n, mac) == 0;
    free(buf);
    if (!ok)
        return -1;
    c->auth.mac_len = AUTH_MAC_BYTES;
    return 0;
}
