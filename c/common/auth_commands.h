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

#endif
