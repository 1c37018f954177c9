#include "managers/mgr_auth.h"

#include <stdio.h>
#include <string.h>

int mgr_auth_init(mgr_auth *a, const char *key_file, const char *who)
{
    memset(a, 0, sizeof *a);
    if (!key_file) {
        fprintf(stderr, "%s: commands are not authenticated (no --key-file)\n", who);
        return 0;
    }
    char err[600];
    if (auth_keys_load(key_file, &a->v.ring, err, sizeof err)) {
        fprintf(stderr, "%s: --key-file %s\n", who, err);
        return -1;
    }
    a->enabled = 1;
    return 0;
}

void mgr_auth_clear(mgr_auth *a) { auth_keys_clear(&a->v.ring); }

auth_result mgr_auth_command(mgr_auth *a, const auv_mission_command_t *c)
{
    return a->enabled ? auth_verify_mission_command(&a->v, c, auth_now_us()) : AUTH_OK;
}

auth_result mgr_auth_upload(mgr_auth *a, const auv_plugin_upload_t *u)
{
    return a->enabled ? auth_verify_plugin_upload(&a->v, u, auth_now_us()) : AUTH_OK;
}
