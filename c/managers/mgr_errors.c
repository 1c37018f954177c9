#include "managers/mgr_errors.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void mgr_errors_add(mgr_errors *e, const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    if (!e || !e->quiet)
        fprintf(stderr, "%s\n", buf);
    if (!e)
        return;
    char **grown = realloc(e->lines, (e->n + 1) * sizeof *grown);
    char *copy = strdup(buf);
    if (!grown || !copy) {
        free(copy);
        if (grown)
            e->lines = grown;
        return;
    }
    e->lines = grown;
    e->lines[e->n++] = copy;
}

void mgr_errors_summary(const mgr_errors *e, size_t max_quoted, char *out, size_t cap)
{
    size_t n = e ? e->n : 0, o = 0;
    if (!cap)
        return;
    out[0] = '\0';
    int w = snprintf(out, cap, "%zu error%s", n, n == 1 ? "" : "s");
    o = w > 0 && (size_t)w < cap ? (size_t)w : cap - 1;
    size_t quoted = 0;
    for (; quoted < n && quoted < max_quoted; quoted++) {
        const char *line = e->lines[quoted];
        /* leave room for the "(and K more)" tail */
        if (o + strlen(line) + 3 + 24 >= cap)
            break;
        w = snprintf(out + o, cap - o, "%s%s", quoted ? "; " : ": ", line);
        if (w < 0 || (size_t)w >= cap - o)
            break;
        o += (size_t)w;
    }
    if (quoted < n)
        snprintf(out + o, cap - o, " (and %zu more)", n - quoted);
}

void mgr_errors_free(mgr_errors *e)
{
    if (!e)
        return;
    for (size_t i = 0; i < e->n; i++)
        free(e->lines[i]);
    free(e->lines);
    e->lines = NULL;
    e->n = 0;
}
