/* Command authentication in the manager (docs/security.md): with
 * --key-file, every mission command and plugin upload must carry a valid
 * command_auth_t before anything else is looked at; without it, none is
 * checked and the manager says so once at start. */
#ifndef MGR_AUTH_H
#define MGR_AUTH_H

#include "common/auth_commands.h"

typedef struct {
    int enabled;            /* --key-file given and loaded */
    auth_verifier v;
} mgr_auth;

/* Loads the key file (NULL: authentication off, said on stderr once).
 * 0, or -1 with the reason said on stderr. */
int mgr_auth_init(mgr_auth *a, const char *key_file, const char *who);
void mgr_auth_clear(mgr_auth *a);
/* AUTH_OK when authentication is off or the message verifies. */
auth_result mgr_auth_command(mgr_auth *a, const auv_mission_command_t *c);
auth_result mgr_auth_upload(mgr_auth *a, const auv_plugin_upload_t *u);

#endif
