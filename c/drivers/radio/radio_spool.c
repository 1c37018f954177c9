#include "drivers/radio/radio_spool.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define META_MAX 4096 /* a meta file is a few hundred bytes */

void rsp_path(const ra_assembler *a, int64_t tid, const char *ext, char *out, size_t cap)
{
    snprintf(out, cap, "%s/%" PRId64 ".%s", a->spool, tid, ext);
}

static int replace_with(const char *tmp, const char *path, const char *text)
{
    FILE *f = fopen(tmp, "w");
    if (!f)
        return -1;
    int ok = fputs(text, f) >= 0;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, path) != 0) {
        remove(tmp);
        return -1;
    }
    return 0;
}

int rsp_save_meta(const ra_assembler *a, const ra_partial *p)
{
    char path[600], tmp[600], text[META_MAX];
    rsp_path(a, p->h.transfer_id, "json", path, sizeof path);
    rsp_path(a, p->h.transfer_id, "tmp", tmp, sizeof tmp);
    /* json.dumps's own spelling, key for key, so the files are alike whoever wrote them */
    snprintf(text, sizeof text,
             "{\"header\": {\"transfer_id\": %" PRId64 ", \"vehicle\": \"%s\", \"channel\": \"%s\", \"count\": %d, "
             "\"total_bytes\": %d, \"sha256_hex\": \"%s\"}, \"next_index\": %d, \"held\": %" PRId64 "}",
             p->h.transfer_id, p->h.vehicle, p->h.channel, (int)p->h.count, (int)p->h.total_bytes, p->h.sha256_hex,
             (int)p->next_index, p->held_bytes);
    return replace_with(tmp, path, text);
}

int rsp_save_done(const ra_assembler *a)
{
    char path[600], tmp[600], text[RA_DONE_KEPT * 24 + 4];
    snprintf(path, sizeof path, "%s/done.json", a->spool);
    snprintf(tmp, sizeof tmp, "%s/done.tmp", a->spool);
    size_t k = 0;
    text[k++] = '[';
    for (int i = 0; i < a->n_done; i++)
        k += (size_t)snprintf(text + k, sizeof text - k, "%s%" PRId64, i ? ", " : "", a->done[i]);
    snprintf(text + k, sizeof text - k, "]");
    return replace_with(tmp, path, text);
}

/* The file's text, NUL-terminated, if it is small enough to be ours. */
static int slurp(const char *path, char *out, size_t cap)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    size_t n = fread(out, 1, cap - 1, f);
    int more = fgetc(f) != EOF;
    fclose(f);
    if (more)
        return -1;
    out[n] = '\0';
    return 0;
}

static const char *skip_ws(const char *s)
{
    while (*s == ' ' || *s == '\n' || *s == '\t' || *s == '\r')
        s++;
    return s;
}

/* The value after "key": in text. */
static const char *value_of(const char *text, const char *key)
{
    char pat[40];
    snprintf(pat, sizeof pat, "\"%s\"", key);
    const char *k = strstr(text, pat);
    if (!k)
        return NULL;
    k = skip_ws(k + strlen(pat));
    return *k == ':' ? skip_ws(k + 1) : NULL;
}

static int int_of(const char *text, const char *key, int64_t lo, int64_t hi, int64_t *out)
{
    const char *v = value_of(text, key);
    if (!v || !(*v == '-' || (*v >= '0' && *v <= '9')))
        return -1;
    char *end;
    errno = 0;
    long long x = strtoll(v, &end, 10);
    if (errno || x < lo || x > hi || !(*end == ',' || *end == '}' || *end == ' '))
        return -1;
    *out = x;
    return 0;
}

/* A string of plain characters (no escapes: ids, channel names, hex). */
static int str_of(const char *text, const char *key, char *out, size_t cap)
{
    const char *v = value_of(text, key);
    if (!v || *v != '"')
        return -1;
    size_t n = 0;
    for (v++; *v != '"'; v++) {
        if (!*v || *v == '\\' || (unsigned char)*v < 0x20 || n + 1 >= cap)
            return -1;
        out[n++] = *v;
    }
    out[n] = '\0';
    return 0;
}

int rsp_load_meta(const char *path, ra_partial *p)
{
    char text[META_MAX];
    int64_t tid, count, total, next, held;
    memset(p, 0, sizeof *p);
    if (slurp(path, text, sizeof text) < 0 || !strstr(text, "\"header\"") ||
        int_of(text, "transfer_id", INT64_MIN + 1, INT64_MAX, &tid) < 0 ||
        int_of(text, "count", 1, RA_MAX_CHUNKS, &count) < 0 ||
        int_of(text, "total_bytes", 1, RA_MAX_BYTES, &total) < 0 ||
        int_of(text, "next_index", 0, count, &next) < 0 || int_of(text, "held", 0, total, &held) < 0 ||
        str_of(text, "vehicle", p->h.vehicle, sizeof p->h.vehicle) < 0 ||
        str_of(text, "channel", p->h.channel, sizeof p->h.channel) < 0 ||
        str_of(text, "sha256_hex", p->h.sha256_hex, sizeof p->h.sha256_hex) < 0)
        return -1;
    p->h.transfer_id = tid;
    p->h.count = (int32_t)count;
    p->h.total_bytes = (int32_t)total;
    p->next_index = (int32_t)next;
    p->held_bytes = held;
    return 0;
}

int rsp_load_done(const char *path, int64_t *ids, int cap)
{
    char text[RA_DONE_KEPT * 64];
    if (slurp(path, text, sizeof text) < 0)
        return -1;
    const char *s = skip_ws(text);
    if (*s++ != '[')
        return -1;
    int n = 0;
    for (s = skip_ws(s); *s != ']';) {
        char *end;
        errno = 0;
        long long x = strtoll(s, &end, 10);
        if (end == s || errno)
            return -1;
        if (n == cap) { /* keep the newest: slide the oldest out */
            memmove(ids, ids + 1, (size_t)(cap - 1) * sizeof *ids);
            n--;
        }
        ids[n++] = x;
        s = skip_ws(end);
        if (*s == ',')
            s = skip_ws(s + 1);
        else if (*s != ']')
            return -1;
    }
    return skip_ws(s + 1)[0] == '\0' ? n : -1;
}
