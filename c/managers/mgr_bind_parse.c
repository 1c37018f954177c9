/* The binding file's syntax: one line per message, words separated by
 * blanks, `#` comments, `include "FILE"` lines (mgr_bind_files.c reads the
 * files). No fixed-size buffer: lines, prefixes and type names
 * have any length; a channel (after ${VEHICLE}) has at most LCM's 63
 * characters; a byte outside printable ASCII, a NUL or a sixth word is an
 * error at its file:line:col. Fuzzed by c/managers/fuzz/fuzz_bindings.c. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "managers/mgr_bind_files.h"
#include "managers/mgr_bindings.h"

static int expand_vehicle(const char *in, const char *vehicle, char *out, size_t outlen)
{
    size_t o = 0;
    for (const char *p = in; *p; p++) {
        if (!strncmp(p, "${VEHICLE}", 10)) {
            size_t n = strlen(vehicle);
            if (o + n >= outlen)
                return -1;
            memcpy(out + o, vehicle, n);
            o += n;
            p += 9;
        } else {
            if (o + 1 >= outlen)
                return -1;
            out[o++] = *p;
        }
    }
    out[o] = '\0';
    return 0;
}

/* One whitespace-separated word of a binding line. */
typedef struct {
    const char *p;
    size_t n;
    int col;
} word_t;

static int word_is(const word_t *w, const char *s) { return w->n == strlen(s) && !memcmp(w->p, s, w->n); }

/* The word as a NUL-terminated copy (or NULL when out of memory). */
static char *word_dup(const word_t *w)
{
    char *s = malloc(w->n + 1);
    if (s) {
        memcpy(s, w->p, w->n);
        s[w->n] = '\0';
    }
    return s;
}

/* Parse one binding line (without its newline). Returns the errors found. */
/* `include "FILE"`: a file name in quotes (blanks in it are not supported). */
static int include_line(mgr_bindings *b, const mgr_bind_chain *chain, int lineno, const word_t *w, int n,
                        const char *vehicle, mgr_errors *errs)
{
    if (n > 2) {
        mgr_errors_add(errs, "%s:%d:%d: one file per include line", chain->path, lineno, w[2].col);
        return 1;
    }
    if (n != 2 || w[1].n < 3 || w[1].p[0] != '"' || w[1].p[w[1].n - 1] != '"') {
        mgr_errors_add(errs, "%s:%d:%d: expected `include \"FILE\"` (a binding file, relative to this one)",
                       chain->path, lineno, n == 2 ? w[1].col : w[0].col);
        return 1;
    }
    word_t inner = {w[1].p + 1, w[1].n - 2, w[1].col + 1};
    char *name = word_dup(&inner);
    if (!name) {
        mgr_errors_add(errs, "%s:%d:1: out of memory", chain->path, lineno);
        return 1;
    }
    int errors = mgr_bind_include(b, chain, lineno, w[1].col, name, vehicle, errs);
    free(name);
    return errors;
}

static int parse_line(mgr_bindings *b, const mgr_bind_chain *chain, int lineno, const char *line, size_t len,
                      const char *vehicle, mgr_errors *errs)
{
    const char *path = chain->path;
    word_t w[6];
    int n = 0;
    size_t end = 0;
    while (end < len && line[end] != '#') end++; /* a comment may hold anything */
    for (size_t i = 0; i < end; i++) {
        unsigned char c = (unsigned char)line[i];
        if ((c < 0x20 && c != '\t' && c != '\r') || c >= 0x7f) {
            mgr_errors_add(errs, "%s:%d:%zu: unexpected byte 0x%02x (binding files are plain ASCII)", path, lineno,
                           i + 1, c);
            return 1;
        }
    }
    for (size_t i = 0; i < end;) {
        if (line[i] == ' ' || line[i] == '\t' || line[i] == '\r') {
            i++;
            continue;
        }
        size_t j = i;
        while (j < end && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') j++;
        if (n == 6) {
            mgr_errors_add(errs, "%s:%d:%zu: unexpected '%.*s' after the line's last field", path, lineno, i + 1,
                           (int)(j - i > 40 ? 40 : j - i), line + i);
            return 1;
        }
        w[n++] = (word_t){line + i, j - i, (int)(i + 1)};
        i = j;
    }
    if (n == 0)
        return 0;
    if (word_is(&w[0], "include"))
        return include_line(b, chain, lineno, w, n, vehicle, errs);
    if (n < 4 || n > 5 || (!word_is(&w[0], "input") && !word_is(&w[0], "output"))) {
        mgr_errors_add(errs, "%s:%d:%d: expected `input|output PREFIX CHANNEL TYPE [optional|on_change]`", path,
                       lineno, w[0].col);
        return 1;
    }
    int is_output = word_is(&w[0], "output");
    /* `optional`: an input that may be absent when the plan starts (GPS
     * only exists at the surface); the plan sees its variables as never
     * written until the first message. `on_change`: an output published
     * only when it changed, and once a second (a status, not a command). */
    const char *flag_error = NULL;
    if (n == 5 && !word_is(&w[4], "optional") && !word_is(&w[4], "on_change"))
        flag_error = "the only flag after the type is `optional` (an input), or `on_change` (an output)";
    else if (n == 5 && word_is(&w[4], "optional") && is_output)
        flag_error = "only an input can be optional";
    else if (n == 5 && word_is(&w[4], "on_change") && !is_output)
        flag_error = "only an output can be on_change";
    if (flag_error) {
        mgr_errors_add(errs, "%s:%d:%d: %s", path, lineno, w[4].col, flag_error);
        return 1;
    }
    char *type = word_dup(&w[3]);
    const auv_type_entry_t *t = type ? auv_type_find(type) : NULL;
    if (!t) {
        mgr_errors_add(errs, "%s:%d:%d: unknown message type '%.*s'", path, lineno, w[3].col,
                       (int)(w[3].n > 60 ? 60 : w[3].n), w[3].p);
        free(type);
        return 1;
    }
    free(type);
    char *prefix = word_dup(&w[1]), *chan = word_dup(&w[2]);
    mgr_message_binding *grown = prefix && chan ? realloc(b->msgs, (size_t)(b->n_msgs + 1) * sizeof *grown) : NULL;
    if (!grown) {
        free(prefix);
        free(chan);
        mgr_errors_add(errs, "%s:%d:1: out of memory", path, lineno);
        return 1;
    }
    b->msgs = grown;
    mgr_message_binding *mb = &b->msgs[b->n_msgs++];
    memset(mb, 0, sizeof *mb);
    mb->is_output = is_output;
    mb->optional = n == 5 && !is_output;
    mb->on_change = n == 5 && is_output;
    mb->prefix = prefix;
    mb->type = t;
    mb->line = lineno;
    mb->file = strdup(path);
    int errors = 0;
    if (!mb->file) {
        mgr_errors_add(errs, "%s:%d:1: out of memory", path, lineno);
        errors++;
    }
    if (expand_vehicle(chan, vehicle, mb->channel, sizeof mb->channel) != 0 || strlen(mb->channel) > MGR_MAX_CHANNEL) {
        mgr_errors_add(errs, "%s:%d:%d: channel name too long (LCM allows %d characters)", path, lineno, w[2].col,
                       MGR_MAX_CHANNEL);
        errors++;
    }
    free(chan);
    for (int k = 0; k < b->n_msgs - 1; k++)
        if (!strcmp(b->msgs[k].prefix, prefix)) {
            const mgr_message_binding *first = &b->msgs[k];
            /* the first binding may be in another file of the include tree */
            int same = first->file && !strcmp(first->file, path);
            mgr_errors_add(errs, "%s:%d:%d: prefix '%s' is already bound %s%s%s%d", path, lineno, w[1].col,
                           strlen(prefix) > 60 ? "(long name)" : prefix, same ? "on line " : "at ",
                           same ? "" : (first->file ? first->file : "?"), same ? "" : ":", first->line);
            errors++;
        }
    return errors;
}

int mgr_bind_parse_chain(mgr_bindings *b, const mgr_bind_chain *chain, const char *text, size_t len,
                         const char *vehicle, mgr_errors *errs)
{
    const char *path = chain->path;
    int lineno = 0, errors = 0;
    for (size_t i = 0; i < len;) {
        size_t e = i;
        while (e < len && text[e] != '\n') e++;
        lineno++;
        if (memchr(text + i, '\0', e - i)) {
            mgr_errors_add(errs, "%s:%d:%zu: unexpected NUL byte", path, lineno,
                           (size_t)((const char *)memchr(text + i, '\0', e - i) - (text + i)) + 1);
            errors++;
        } else
            errors += parse_line(b, chain, lineno, text + i, e - i, vehicle, errs);
        i = e + 1;
    }
    return errors;
}

int mgr_bindings_parse_text(mgr_bindings *b, const char *path, const char *text, size_t len, const char *vehicle,
                            mgr_errors *errs)
{
    char *real = realpath(path, NULL); /* NULL when no such file: then only its includes can cycle */
    mgr_bind_chain top = {path, real, NULL, 0};
    int errors = mgr_bind_parse_chain(b, &top, text, len, vehicle, errs);
    free(real);
    return errors;
}
