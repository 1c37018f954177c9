/* Fuzz entry point for auv-radio (c/drivers/radio): the input is a script of
 * chunks for the reassembly (radio_asm.h), 8 bytes each: transfer (1 of 6),
 * index, count, size, chunk length, digest right or wrong, header fields right
 * or not, a jump of time (expiry) or a restart from the spool. The whole of a
 * transfer is a fixed pattern, so a right digest can complete one. Whatever
 * the order: at most RA_MAX_TRANSFERS partial transfers, on disk too; a whole
 * handed on is exactly its pattern, of its declared size, and never twice;
 * every refusal is counted. The input's bytes also go through the byte pipe
 * and the protocol (libFuzzer, or c/chasm/fuzz/fuzz_driver.c). */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "common/auth_mac.h"
#include "drivers/radio/radio.h"

#define N_IDS 6
#define MAX_OPS 32

static char spool[64];

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "fuzz_radio: broken: %s\n", what);
        abort();
    }
}

static int count_files(const char *ext, int unlink_them)
{
    DIR *d = opendir(spool);
    int n = 0;
    struct dirent *e;
    char path[64 + 256 + 2];
    while (d && (e = readdir(d)) != NULL) {
        size_t k = strlen(e->d_name), m = strlen(ext);
        if (e->d_name[0] == '.' || k <= m || strcmp(e->d_name + k - m, ext))
            continue;
        n++;
        if (unlink_them) {
            snprintf(path, sizeof path, "%s/%s", spool, e->d_name);
            unlink(path);
        }
    }
    if (d)
        closedir(d);
    return n;
}

static uint8_t pattern_byte(int64_t tid, int32_t i) { return (uint8_t)(i * 31 + tid * 7); }

static uint8_t whole[RA_MAX_BYTES / 64]; /* the patterns the script may complete: sizes up to 65535 */

static void remove_spool(void)
{
    count_files("", 1);
    rmdir(spool);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!spool[0]) {
        /* in memory where there is /dev/shm: an input is dozens of small writes */
        snprintf(spool, sizeof spool, "%s/fuzz_radio.XXXXXX", access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp");
        check(mkdtemp(spool) != NULL, "a spool");
        atexit(remove_spool);
    }
    count_files("", 1);
    drv_ctx ctx;
    drv_ctx_init(&ctx, "fuzz_radio", "FUZZ", "RADIO", NULL, NULL);
    ctx.quiet = 1;
    ra_assembler *a = calloc(1, sizeof *a);
    char err[200];
    check(a && ra_open(a, &ctx, "FUZZ", spool, 600, err, sizeof err) == 0, "open");
    int delivered[N_IDS] = {0};
    double t = 1e9;
    for (size_t at = 0; at + 8 <= size && at / 8 < MAX_OPS; at += 8) {
        const uint8_t *op = data + at;
        int64_t tid = op[0] % N_IDS;
        int kind = op[0] >> 5;
        if (kind == 7) { /* a restart: what the spool holds comes back */
            free(a);
            a = calloc(1, sizeof *a);
            check(a && ra_open(a, &ctx, "FUZZ", spool, 600, err, sizeof err) == 0, "reopen");
            continue;
        }
        t += kind == 6 ? 1000 : 1;
        int32_t total = (int32_t)(op[3] << 8 | op[4]);
        int32_t count = op[2] == 255 ? 1 << 30 : op[2];
        int32_t per = count > 0 && count < (1 << 30) ? (total + count - 1) / count : 1;
        int32_t index = (int8_t)op[1];
        int32_t n = op[5] & 1 ? per : op[5] * 17; /* mostly its share, now and then any length */
        if (index >= 0 && index == count - 1 && op[5] & 1)
            n = total - per * (count - 1);
        if (n < 0 || n > 4096)
            n = 1;
        static uint8_t chunk[4096];
        for (int32_t i = 0; i < n; i++)
            chunk[i] = pattern_byte(tid, index * per + i);
        for (int32_t i = 0; i < total; i++)
            whole[i] = pattern_byte(tid, i);
        char sha[65];
        auth_sha256_hex(whole, (size_t)total, sha);
        if (op[6] & 1)
            sha[op[6] % 64] = sha[op[6] % 64] == '0' ? '1' : '0';
        auv_radio_chunk_t c = {.utime = 0, .transfer_id = tid, .vehicle = op[7] == 1 ? "AUV9" : "FUZZ",
                               .channel = op[7] == 2 ? "CHASM.X" : (op[7] & 4 ? "PLUGIN_UPLOAD" : "MISSION_CMD"),
                               .index = index, .count = count, .total_bytes = total, .sha256_hex = sha,
                               .n_bytes = n, .data = chunk};
        int64_t refused = a->refused;
        ra_offer o;
        ra_offer_chunk(a, &ctx, &c, t, &o);
        check(o.state >= RA_HOLDING && o.state <= RA_REFUSED, "a state");
        check(!*o.reason || a->refused > refused || o.state == RA_DONE, "a refusal is counted");
        if (o.data) {
            check(o.len == (size_t)total && !memcmp(o.data, whole, o.len), "the whole is its pattern");
            check(!delivered[tid]++, "never handed on twice");
        }
        ra_offer_free(&o);
        int64_t ids[RA_MAX_TRANSFERS + 1];
        int32_t next[RA_MAX_TRANSFERS + 1];
        check(ra_holding(a, ids, next, RA_MAX_TRANSFERS + 1) <= RA_MAX_TRANSFERS, "bounded partials");
        for (int i = 0; i < RA_MAX_TRANSFERS; i++)
            check(!a->p[i].used || a->p[i].held_bytes <= a->p[i].h.total_bytes, "held within the size");
    }
    check(count_files(".part", 0) <= RA_MAX_TRANSFERS, "bounded spool");
    free(a);

    /* the same bytes as a stream from the radio, cut into reads the input chooses */
    radio_state *s = calloc(1, sizeof *s);
    check(s && radio_protocol.init(s, &ctx) == 0, "init");
    unsigned cut = size ? data[0] : 5;
    for (size_t i = 0; i < size;) {
        size_t k = 1 + (cut + i) % 251;
        if (k > size - i)
            k = size - i;
        radio_protocol.feed(s, &ctx, data + i, k, 1000000 + (int64_t)i);
        i += k;
    }
    check(s->pipe.len <= sizeof s->pipe.buf && s->delivered == 0, "bounded, and no spool: nothing delivered");
    free(s);
    return 0;
}
