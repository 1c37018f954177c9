/* The plugin folder a program finds on its own: the plugins built beside it.
 *
 * A build puts programs in <build>/bin and plugins in <build>/plugins (the
 * sanitizer build likewise under build/san), so a program that was given no
 * plugin path looks in ../plugins next to its own executable: `chasm check
 * plan.chasm` and `chasm-manager --plan ...` then work on a fresh build with
 * no options, and each build finds its own plugins. */

#include <limits.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "chasm/chasm.h"

int chasm_default_plugin_dir(char *out, size_t cap)
{
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) return 0;
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (!slash) return 0;
    *slash = '\0';
    char dir[PATH_MAX + 16];
    snprintf(dir, sizeof dir, "%s/../plugins", exe);
    char real[PATH_MAX];
    struct stat st;
    if (!realpath(dir, real) || stat(real, &st) || !S_ISDIR(st.st_mode)) return 0;
    if (strlen(real) + 1 > cap) return 0;
    memcpy(out, real, strlen(real) + 1);
    return 1;
}
