#include "drivers/radio/radio_asm.h"

#include <dirent.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "common/auth_mac.h"
#include "drivers/radio/radio_spool.h"

static const char *const CHANNELS[] = {"MISSION_CMD", "PLUGIN_UPLOAD"}; /* what the radio may publish */

static void forget(ra_assembler *a, int64_t tid)
{
    char path[600];
    for (int i = 0; i < RA_MAX_TRANSFERS; i++)
        if (a->p[i].used && a->p[i].h.transfer_id == tid)
            a->p[i].used = 0;
    rsp_path(a, tid, "part", path, sizeof path);
    unlink(path);
    rsp_path(a, tid, "json", path, sizeof path);
    unlink(path);
}

static ra_partial *find(ra_assembler *a, int64_t tid)
{
    for (int i = 0; i < RA_MAX_TRANSFERS; i++)
        if (a->p[i].used && a->p[i].h.transfer_id == tid)
            return &a->p[i];
    return NULL;
}

static ra_partial *take_slot(ra_assembler *a)
{
    for (int i = 0; i < RA_MAX_TRANSFERS; i++)
        if (!a->p[i].used) {
            memset(&a->p[i], 0, sizeof a->p[i]);
            a->p[i].used = 1;
            a->arrived[i] = ++a->order;
            return &a->p[i];
        }
    return NULL;
}

static int is_done(const ra_assembler *a, int64_t tid)
{
    for (int i = 0; i < a->n_done; i++)
        if (a->done[i] == tid)
            return 1;
    return 0;
}

static void count(ra_assembler *a, drv_ctx *ctx, const char *reason, const char *detail)
{
    a->refused++;
    drv_drop(ctx, reason, "%s", detail);
}

/* The names in dir ending in ext (done.json aside), sorted; at most cap. */
static int list(const char *dir, const char *ext, char names[][80], int cap)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int n = 0;
    size_t m = strlen(ext);
    struct dirent *e;
    while ((e = readdir(d)) != NULL && n < cap) {
        size_t len = strlen(e->d_name);
        if (len > m && len < 80 && !strcmp(e->d_name + len - m, ext) && strcmp(e->d_name, "done.json"))
            strcpy(names[n++], e->d_name);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], (int (*)(const void *, const void *))strcmp);
    return n;
}

static void load(ra_assembler *a, drv_ctx *ctx)
{
    char path[600];
    snprintf(path, sizeof path, "%s/done.json", a->spool);
    if (access(path, F_OK) == 0) {
        int n = rsp_load_done(path, a->done, RA_DONE_KEPT);
        if (n < 0)
            count(a, ctx, "spool: unreadable done list", path);
        a->n_done = n < 0 ? 0 : n;
    }
    /* in the order of the names, as the Python's sorted glob */
    char names[64][80];
    int n = list(a->spool, ".json", names, 64);
    for (int i = 0; i < n; i++) {
        ra_partial p;
        snprintf(path, sizeof path, "%s/%.79s", a->spool, names[i]);
        char data[600];
        int ok = rsp_load_meta(path, &p) == 0 && !find(a, p.h.transfer_id);
        if (ok) {
            rsp_path(a, p.h.transfer_id, "part", data, sizeof data);
            struct stat st;
            ok = stat(data, &st) == 0 && st.st_size >= p.held_bytes && truncate(data, p.held_bytes) == 0;
        }
        if (!ok) {
            count(a, ctx, "spool: unreadable partial transfer", path);
            char *end;
            long long tid = strtoll(names[i], &end, 10);
            if (end != names[i] && !strcmp(end, ".json"))
                forget(a, tid);
            unlink(path);
            continue;
        }
        ra_partial *slot = take_slot(a);
        if (!slot) {
            forget(a, p.h.transfer_id);
            continue;
        }
        *slot = p;
        slot->used = 1;
        slot->last_s = NAN; /* idle from now on: the spool does not say since when */
    }
    /* bytes whose meta is gone or was never written: nothing can resume them */
    n = list(a->spool, ".part", names, 64);
    for (int i = 0; i < n; i++) {
        char *end;
        long long tid = strtoll(names[i], &end, 10);
        if (end != names[i] && !strcmp(end, ".part") && find(a, tid))
            continue;
        snprintf(path, sizeof path, "%s/%.79s", a->spool, names[i]);
        count(a, ctx, "spool: bytes without meta", path);
        unlink(path);
    }
}

int ra_open(ra_assembler *a, drv_ctx *ctx, const char *vehicle, const char *spool, double idle_expiry_s, char *err,
            size_t errlen)
{
    memset(a, 0, sizeof *a);
    snprintf(a->vehicle, sizeof a->vehicle, "%s", vehicle);
    snprintf(a->spool, sizeof a->spool, "%s", spool);
    a->idle_expiry_s = idle_expiry_s;
    /* the folder and its parents, as mkdir -p */
    char path[sizeof a->spool];
    snprintf(path, sizeof path, "%s", spool);
    for (char *s = path + 1; *s; s++)
        if (*s == '/') {
            *s = '\0';
            mkdir(path, 0700);
            *s = '/';
        }
    if (mkdir(path, 0700) != 0 && errno != EEXIST) {
        snprintf(err, errlen, "cannot make the spool %s: %s", spool, strerror(errno));
        return -1;
    }
    load(a, ctx);
    return 0;
}

int ra_expire(ra_assembler *a, drv_ctx *ctx, double now_s)
{
    int n = 0;
    for (int i = 0; i < RA_MAX_TRANSFERS; i++) {
        ra_partial *p = &a->p[i];
        if (!p->used)
            continue;
        if (isnan(p->last_s))
            p->last_s = now_s;
        if (now_s - p->last_s > a->idle_expiry_s) {
            char d[80];
            snprintf(d, sizeof d, "transfer %" PRId64 " idle for %.0f s", p->h.transfer_id, now_s - p->last_s);
            count(a, ctx, "never ended: expired", d);
            forget(a, p->h.transfer_id);
            n++;
        }
    }
    return n;
}

int ra_holding(const ra_assembler *a, int64_t *ids, int32_t *next, int cap)
{
    int n = 0;
    uint64_t after = 0;
    for (;;) { /* in order of arrival: the smallest arrival above the last one taken */
        int best = -1;
        for (int i = 0; i < RA_MAX_TRANSFERS; i++)
            if (a->p[i].used && a->arrived[i] > after && (best < 0 || a->arrived[i] < a->arrived[best]))
                best = i;
        if (best < 0 || n == cap)
            return n;
        ids[n] = a->p[best].h.transfer_id;
        next[n++] = a->p[best].next_index;
        after = a->arrived[best];
    }
}

static void answer(ra_offer *o, int32_t next, int state, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static void answer(ra_offer *o, int32_t next, int state, const char *fmt, ...)
{
    o->next_index = next;
    o->state = state;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(o->reason, sizeof o->reason, fmt, ap);
    va_end(ap);
}

/* As answer(), and counted under key. */
#define REFUSE(key, next, state, ...)                     \
    do {                                                  \
        answer(o, next, state, __VA_ARGS__);              \
        count(a, ctx, key, o->reason);                    \
    } while (0)

static int is_hex64(const char *s)
{
    size_t n = 0;
    for (; s[n]; n++)
        if (!((s[n] >= '0' && s[n] <= '9') || (s[n] >= 'a' && s[n] <= 'f')))
            return 0;
    return n == 64;
}

/* What every chunk's header must hold; the refusal's key and text, or NULL. */
static const char *check_header(const ra_assembler *a, const auv_radio_chunk_t *c, char *why, size_t cap)
{
    if (strcmp(c->vehicle, a->vehicle)) {
        snprintf(why, cap, "addressed to '%.60s', this is %s", c->vehicle, a->vehicle);
        return "wrong vehicle";
    }
    if (strcmp(c->channel, CHANNELS[0]) && strcmp(c->channel, CHANNELS[1])) {
        snprintf(why, cap, "channel '%.60s' is not carried (only %s, %s)", c->channel, CHANNELS[0], CHANNELS[1]);
        return "channel";
    }
    if (!is_hex64(c->sha256_hex)) {
        snprintf(why, cap, "sha256_hex is not 64 lowercase hex digits");
        return "bad digest";
    }
    if (!(c->total_bytes > 0 && c->total_bytes <= RA_MAX_BYTES)) {
        snprintf(why, cap, "%d bytes: at most %d", (int)c->total_bytes, RA_MAX_BYTES);
        return "too large";
    }
    int32_t most = c->total_bytes < RA_MAX_CHUNKS ? c->total_bytes : RA_MAX_CHUNKS;
    if (!(c->count > 0 && c->count <= most)) {
        snprintf(why, cap, "%d chunks for %d bytes", (int)c->count, (int)c->total_bytes);
        return "too many";
    }
    if ((int64_t)c->count * RA_MAX_CHUNK_BYTES < c->total_bytes) {
        snprintf(why, cap, "%d chunks cannot hold %d bytes", (int)c->count, (int)c->total_bytes);
        return "too few";
    }
    if (!(c->index >= 0 && c->index < c->count)) {
        snprintf(why, cap, "chunk %d of %d", (int)c->index, (int)c->count);
        return "too many";
    }
    return NULL;
}

static int same_header(const ra_header *h, const auv_radio_chunk_t *c)
{
    return !strcmp(h->vehicle, c->vehicle) && !strcmp(h->channel, c->channel) && h->count == c->count &&
           h->total_bytes == c->total_bytes && !strcmp(h->sha256_hex, c->sha256_hex);
}

static int append(const ra_assembler *a, int64_t tid, const uint8_t *data, size_t n, const char *mode)
{
    char path[600];
    rsp_path(a, tid, "part", path, sizeof path);
    FILE *f = fopen(path, mode);
    if (!f)
        return -1;
    int ok = n == 0 || fwrite(data, 1, n, f) == n; /* (fwrite takes no NULL, even for 0 bytes) */
    return (fclose(f) == 0 && ok) ? 0 : -1;
}

/* The whole from the spool, checked against its digest; the transfer is forgotten either way. */
static void finish(ra_assembler *a, drv_ctx *ctx, ra_partial *p, ra_offer *o)
{
    char path[600], hex[65];
    int64_t tid = p->h.transfer_id;
    size_t n = (size_t)p->h.total_bytes;
    rsp_path(a, tid, "part", path, sizeof path);
    uint8_t *whole = malloc(n);
    FILE *f = fopen(path, "rb");
    int ok = whole && f && fread(whole, 1, n, f) == n;
    if (f)
        fclose(f);
    ra_header h = p->h;
    int32_t next = p->next_index;
    forget(a, tid);
    if (ok)
        auth_sha256_hex(whole, n, hex);
    if (!ok || strcmp(hex, h.sha256_hex)) {
        free(whole);
        REFUSE(ok ? "wrong digest" : "spool error", 0, RA_REFUSED, "%s",
               ok ? "the whole does not match its SHA-256: dropped" : "the spool lost the transfer: dropped");
        return;
    }
    if (a->n_done == RA_DONE_KEPT) {
        memmove(a->done, a->done + 1, (RA_DONE_KEPT - 1) * sizeof a->done[0]);
        a->n_done--;
    }
    a->done[a->n_done++] = tid;
    rsp_save_done(a);
    answer(o, next, RA_DONE, "%s", "");
    o->channel = !strcmp(h.channel, CHANNELS[0]) ? CHANNELS[0] : CHANNELS[1];
    o->data = whole;
    o->len = n;
}

void ra_offer_chunk(ra_assembler *a, drv_ctx *ctx, const auv_radio_chunk_t *c, double now_s, ra_offer *o)
{
    memset(o, 0, sizeof *o);
    int64_t tid = c->transfer_id;
    if (is_done(a, tid)) {
        REFUSE("duplicate", c->count, RA_DONE, "duplicate: transfer already delivered");
        return;
    }
    ra_partial *p = find(a, tid);
    char why[160];
    const char *bad = check_header(a, c, why, sizeof why);
    if (bad) { /* one bad chunk never costs a transfer held so far */
        REFUSE(bad, p ? p->next_index : 0, p ? RA_HOLDING : RA_REFUSED, "%s", why);
        return;
    }
    if (!p) {
        if (c->index != 0) {
            REFUSE("unknown transfer", 0, RA_HOLDING, "chunk %d of a transfer not held: send from 0", (int)c->index);
            return;
        }
        ra_expire(a, ctx, now_s);
        p = take_slot(a);
        if (!p) {
            REFUSE("busy", 0, RA_REFUSED, "%d transfers already in progress: try later", RA_MAX_TRANSFERS);
            return;
        }
        p->h.transfer_id = tid;
        snprintf(p->h.vehicle, sizeof p->h.vehicle, "%s", c->vehicle);
        snprintf(p->h.channel, sizeof p->h.channel, "%s", c->channel);
        p->h.count = c->count;
        p->h.total_bytes = c->total_bytes;
        snprintf(p->h.sha256_hex, sizeof p->h.sha256_hex, "%s", c->sha256_hex);
        if (append(a, tid, NULL, 0, "wb") < 0 || rsp_save_meta(a, p) < 0) { /* a restart knows it from now on */
            forget(a, tid);
            REFUSE("spool error", 0, RA_REFUSED, "cannot write the spool %s", a->spool);
            return;
        }
    } else if (!same_header(&p->h, c)) {
        REFUSE("another transfer", p->next_index, RA_HOLDING, "chunk %d does not match transfer %" PRId64 "'s header",
               (int)c->index, tid);
        return;
    }
    p->last_s = now_s;
    if (c->index < p->next_index) {
        REFUSE("duplicate", p->next_index, RA_HOLDING, "duplicate chunk %d", (int)c->index);
        return;
    }
    if (c->index > p->next_index) {
        REFUSE("out of order", p->next_index, RA_HOLDING, "chunk %d out of order: expected %d", (int)c->index,
               (int)p->next_index);
        return;
    }
    int64_t n = c->n_bytes, held = p->held_bytes;
    if (!(n > 0 && n <= RA_MAX_CHUNK_BYTES)) {
        REFUSE("bad chunk", p->next_index, RA_HOLDING, "chunk %d: %d bytes", (int)c->index, (int)n);
        return;
    }
    if (held + n > c->total_bytes) {
        REFUSE("too many", p->next_index, RA_HOLDING, "chunk %d goes past the declared %d bytes", (int)c->index,
               (int)c->total_bytes);
        return;
    }
    if (c->index == c->count - 1 && held + n != c->total_bytes) {
        REFUSE("too few", p->next_index, RA_HOLDING, "%" PRId64 " of %d bytes at the last chunk", held + n,
               (int)c->total_bytes);
        return;
    }
    if (append(a, tid, c->data, (size_t)n, "ab") < 0) {
        REFUSE("spool error", p->next_index, RA_HOLDING, "cannot write the spool %s", a->spool);
        return;
    }
    p->next_index++;
    p->held_bytes += n;
    if (p->next_index < c->count) {
        rsp_save_meta(a, p);
        answer(o, p->next_index, RA_HOLDING, "%s", "");
        return;
    }
    finish(a, ctx, p, o);
}

void ra_offer_free(ra_offer *o)
{
    free(o->data);
    o->data = NULL;
}
