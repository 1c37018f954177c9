/* libFuzzer target for the plugin loader's file check: any bytes as a plugin
 * file. cm_elf_check must never read outside the buffer (ASan) and, for every
 * input it accepts, the whole open (private copy, probe process, dlopen,
 * descriptor check) must end in a plugin or an error, never a signal in this
 * process. Seed it with real plugins (build/san/plugins/). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "chasm/chasm.h"
#include "chasm/cm_elf_check.h"
#include "chasm/cm_plugin_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int mkstemps(char *, int);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[1024];
    if (cm_elf_check(data, size, err, sizeof err)) return 0;
    /* Accepted: the full open must cope. A hung constructor costs the probe
     * timeout, so keep it short here. */
    cm_plugin_probe_ms = 1000;
    const char *t = getenv("TMPDIR");
    char path[4200];
    snprintf(path, sizeof path, "%s/chasm-fuzz-XXXXXX.so", t && t[0] ? t : "/tmp");
    int fd = mkstemps(path, 3);
    if (fd < 0) return 0;
    int ok = write(fd, data, size) == (ssize_t)size;
    close(fd);
    if (ok) {
        chasm_plugin_file *f = chasm_plugin_file_open(path, NULL, err, sizeof err);
        chasm_plugin_file_close(f);
    }
    unlink(path);
    return 0;
}
