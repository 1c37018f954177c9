/* Reading binding files, and `include "FILE"`: a line shared by several
 * binding files (a sensor's input) is written once, in a file they include.
 * An included name is resolved relative to the folder of the file that
 * names it, as a C compiler does, so the files move together. Refused, each
 * at the include's file:line:col: a file that cannot be opened or is not a
 * regular file (a FIFO would block the manager), a cycle (named file by
 * file), and nesting deeper than MGR_MAX_BIND_INCLUDE_DEPTH. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "managers/mgr_bind_files.h"
#include "managers/mgr_bindings.h"

/* The whole file in a malloc'd buffer (*len bytes), or NULL after reporting
 * why at `where` ("path" for the top file, "includer:line:col" otherwise). */
static char *read_all(const char *path, const char *where, size_t *len, mgr_errors *errs)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (where == path)
            mgr_errors_add(errs, "%s: cannot open binding file", path);
        else
            mgr_errors_add(errs, "%s: cannot open included binding file %s: %s", where, path, strerror(errno));
        return NULL;
    }
    size_t cap = 4096, n = 0, r;
    char *buf = malloc(cap);
    while (buf && (r = fread(buf + n, 1, cap - n, f)) > 0) {
        n += r;
        if (n == cap && n < MGR_MAX_BIND_BYTES + 1) {
            char *g = realloc(buf, cap * 2);
            if (!g) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = g;
            cap *= 2;
        } else if (n == cap)
            break;
    }
    fclose(f);
    if (!buf) {
        mgr_errors_add(errs, "%s: out of memory reading the binding file %s", where, path);
        return NULL;
    }
    if (n > MGR_MAX_BIND_BYTES) {
        mgr_errors_add(errs, "%s:1:1: binding file larger than %d bytes", path, MGR_MAX_BIND_BYTES);
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

static int parse_chain_file(mgr_bindings *b, const mgr_bind_chain *chain, const char *where, const char *vehicle,
                            mgr_errors *errs)
{
    size_t len = 0;
    char *text = read_all(chain->path, where, &len, errs);
    if (!text)
        return 1;
    int errors = mgr_bind_parse_chain(b, chain, text, len, vehicle, errs);
    free(text);
    return errors;
}

int mgr_bindings_parse_file(mgr_bindings *b, const char *path, const char *vehicle, mgr_errors *errs)
{
    char *real = realpath(path, NULL);
    mgr_bind_chain top = {path, real, NULL, 0};
    int errors = parse_chain_file(b, &top, path, vehicle, errs);
    free(real);
    return errors;
}

/* "a.bind -> b.bind -> a.bind": the chain from the top file to `closing`. */
static void cycle_text(const mgr_bind_chain *chain, const char *closing, char *out, size_t cap)
{
    const char *names[MGR_MAX_BIND_INCLUDE_DEPTH + 1];
    int n = 0;
    for (const mgr_bind_chain *c = chain; c && n < MGR_MAX_BIND_INCLUDE_DEPTH + 1; c = c->up) names[n++] = c->path;
    size_t o = 0;
    out[0] = '\0';
    for (int i = n - 1; i >= 0 && o < cap; i--) o += (size_t)snprintf(out + o, cap - o, "%s -> ", names[i]);
    if (o < cap)
        snprintf(out + o, cap - o, "%s", closing);
}

int mgr_bind_include(mgr_bindings *b, const mgr_bind_chain *chain, int lineno, int col, const char *name,
                     const char *vehicle, mgr_errors *errs)
{
    char where[512];
    snprintf(where, sizeof where, "%s:%d:%d", chain->path, lineno, col);
    if (chain->depth + 1 >= MGR_MAX_BIND_INCLUDE_DEPTH) {
        mgr_errors_add(errs, "%s: includes nested deeper than %d files", where, MGR_MAX_BIND_INCLUDE_DEPTH);
        return 1;
    }
    /* relative to the including file's folder; an absolute name as it is */
    const char *slash = strrchr(chain->path, '/');
    size_t dir = name[0] == '/' || !slash ? 0 : (size_t)(slash - chain->path) + 1;
    size_t n = dir + strlen(name) + 1;
    char *path = malloc(n);
    if (!path) {
        mgr_errors_add(errs, "%s: out of memory", where);
        return 1;
    }
    snprintf(path, n, "%.*s%s", (int)dir, chain->path, name);
    struct stat st;
    char *real = NULL;
    int errors = 0;
    if (stat(path, &st) != 0) {
        mgr_errors_add(errs, "%s: cannot include '%s' (%s): %s", where, name, path, strerror(errno));
        errors = 1;
    } else if (!S_ISREG(st.st_mode)) {
        mgr_errors_add(errs, "%s: cannot include '%s' (%s): not a regular file", where, name, path);
        errors = 1;
    } else if (!(real = realpath(path, NULL))) {
        mgr_errors_add(errs, "%s: cannot include '%s' (%s): %s", where, name, path, strerror(errno));
        errors = 1;
    }
    for (const mgr_bind_chain *c = chain; !errors && c; c = c->up)
        if (c->real && !strcmp(c->real, real)) {
            char cycle[1024];
            cycle_text(chain, path, cycle, sizeof cycle);
            mgr_errors_add(errs, "%s: include cycle: %s", where, cycle);
            errors = 1;
        }
    if (!errors) {
        mgr_bind_chain next = {path, real, chain, chain->depth + 1};
        errors = parse_chain_file(b, &next, where, vehicle, errs);
    }
    free(real);
    free(path);
    return errors;
}
