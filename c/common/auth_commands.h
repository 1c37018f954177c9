/* Verifying the command types that carry a command_auth_t: each is
 * re-encoded with mac_len 0 (LCM's encoding of a message is unique, so this
 * is the signed byte string) and handed to auth_verify. */
#ifndef AUV_AUTH_COMMANDS_H
#define AUV_AUTH_COMMANDS_H

#include "auv/auv_mission_command_t.h"
#include "auv/auv_plugin_upload_t.h"
#include "common/auth_verify.h"

auth_result auth_verify_mission_command(auth_verifier *v, const auv_mission_command_t *c, int64_t now_us);
auth_result auth_verify_plugin_upload(auth_verifier *v, const auv_plugin_upload_t *u, int64_t now_us);

/* Signs c in place with key, as python/auvlcm/auth.py's sign(): key_id,
 * sender (cut to AUTH_MAX_SENDER), counter (microseconds since the epoch,
 * strictly increasing per sender: the caller's), then the HMAC-SHA-256 over
 * the encoding with mac_len 0 into mac[], which must hold AUTH_MAC_BYTES and
 * stays the caller's (c->auth.mac points to it). Every other field must be
 * final. 0, or -1 if it cannot be encoded or libcrypto fails. */
int auth_sign_mission_command(auv_mission_command_t *c, const auth_key *key, const char *sender, int64_t counter,
                              char sender_buf[AUTH_MAX_SENDER + 1], uint8_t mac[AUTH_MAC_BYTES]);

#endif
