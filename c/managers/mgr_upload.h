/* Plugin uploads (<VEHICLE>.PLUGIN_UPLOAD). The rule: a plugin file exists in
 * --plugin-dir only after it loaded and passed. An upload is refused unless
 * its name is a plugin name, its data matches its SHA-256 and the allowlist
 * has a line "DIGEST NAME" for exactly that digest and name. It is written to
 * a hidden temporary file in the plugin directory, synced, opened the way the
 * Loader opens every plugin (ELF check, probe process, ABI, symbol, schema,
 * the name it claims), hot-loaded if the running plan uses it, and only then
 * renamed to chasm_NAME.so; on any failure the temporary file is deleted. */
#ifndef MGR_UPLOAD_H
#define MGR_UPLOAD_H
#include <stddef.h>
#include <stdint.h>

#include "auv/auv_plugin_upload_t.h"
#include "managers/manager.h"

/* Handles one upload: the ack result (AUV_MISSION_ACK_T_RESULT_*) and its text. */
int8_t mgr_upload_plugin(manager_t *mg, const auv_plugin_upload_t *u, char *text, size_t tl);
/* Deletes temporary files an interrupted upload left in the plugin directory. */
void mgr_upload_clean_dir(const manager_t *mg);
#endif
