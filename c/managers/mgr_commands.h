/* Mission commands (<VEHICLE>.MISSION_CMD) and plugin uploads
 * (<VEHICLE>.PLUGIN_UPLOAD), each answered on <VEHICLE>.MISSION_ACK
 * (mgr_commands.c; uploads in mgr_upload.c). */
#ifndef MGR_COMMANDS_H
#define MGR_COMMANDS_H

#include <stdint.h>

#include "managers/manager.h"

int mgr_commands_subscribe(manager_t *mg);
void mgr_commands_unsubscribe(manager_t *mg);
uint64_t mgr_commands_decode_errors(const manager_t *mg);

#endif
