/* Opening one plugin file so that no file can take the process down.
 *
 * Any file a loader is given (a -P directory, $CHASM_PLUGIN_PATH, a hot plug,
 * a manager upload) goes through cm_plugin_code_open:
 *   1. read it whole: a regular file, 1 byte to CM_PLUGIN_MAX_BYTES;
 *   2. cm_elf_check on those bytes (cm_elf_check.h);
 *   3. write exactly those bytes to a private copy in $TMPDIR (a file changed
 *      or truncated later cannot change what is mapped, and dlopen gives
 *      every version its own handle);
 *   4. probe: a forked child dlopens the copy, finds the descriptor and checks
 *      ABI and schema; a child that dies by a signal, exits by itself or
 *      hangs for CM_PLUGIN_PROBE_MS refuses the file;
 *   5. only then the process itself dlopens the copy and checks again. */
#ifndef CM_PLUGIN_FILE_H
#define CM_PLUGIN_FILE_H
#include <stddef.h>

#include "chasm/chasm_plugin.h"

#define CM_PLUGIN_PROBE_MS 2000 /* a good plugin takes 1-30 ms; a manager's cycle waits */

typedef struct {
    void *dl;
    const chasm_plugin_descriptor *desc;
    chasm_plugin_check_fn check;  /* optional (chasm_plugin.h), NULL if absent */
} cm_plugin_code;

/* How long a probe may take, in ms (CM_PLUGIN_PROBE_MS; the fuzzer lowers it). */
extern int cm_plugin_probe_ms;

/* 0 and out filled, or -1 with the reason in err. */
int cm_plugin_code_open(const char *path, cm_plugin_code *out, char *err, size_t errlen);
void cm_plugin_code_close(cm_plugin_code *c);
#endif
