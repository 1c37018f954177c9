/* auv-auth-probe: the C side of command authentication (c/common/auth_*.h)
 * for tests in both builds and for checking a key file by hand.
 *
 *   auv-auth-probe keys FILE
 *       Load a key file as the managers do: its key ids, the signing one last;
 *       exit 1 with the reason when it is refused (loose mode, bad line).
 *   auv-auth-probe vectors FILE
 *       Check every line of the shared test vectors (tests/auth/vectors.txt):
 *         hmac KEYHEX DATAHEX MACHEX
 *         acoustic KEYHEX COUNTER PAYLOADHEX TAGHEX
 *       '#' comments. Prints "ok N", or each mismatch and exit 1.
 *   auv-auth-probe verify KEYFILE NOW_US MSGFILE...
 *       Offer each encoded mission_command_t or plugin_upload_t to one
 *       verifier, in order, at this clock: one result name per file.
 *   auv-auth-probe acoustic KEYHEX COUNTER:PAYLOADHEX:TAGHEX...
 *       Offer each frame to one acoustic window: 0 ok, 1 bad tag, 2 replay,
 *       3 too old, one a line.
 *   auv-auth-probe bench KEYFILE MSGFILE N
 *       Decode the encoded signed mission_command_t N times, then decode and
 *       verify it N times (each with a new verifier: no replay): the cost per
 *       message of each, in ns (bench/auth_bench.py).
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "common/auth_acoustic.h"
#include "common/auth_commands.h"
#include "common/auv_types.h"
#include "common/lcm_rx.h"

static size_t unhex(const char *s, uint8_t *out, size_t cap)
{
    size_t n = strlen(s) / 2;
    if (n > cap || strlen(s) % 2)
        return (size_t)-1;
    for (size_t i = 0; i < n; i++) {
        unsigned v;
        if (sscanf(s + 2 * i, "%2x", &v) != 1)
            return (size_t)-1;
        out[i] = (uint8_t)v;
    }
    return n;
}

static unsigned char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, n = 0;
    unsigned char *buf = malloc(cap);
    size_t got;
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            unsigned char *b = realloc(buf, cap *= 2);
            if (!b) {
                free(buf);
                buf = NULL;
            }
            buf = b;
        }
    }
    fclose(f);
    *len = n;
    return buf;
}

static int cmd_keys(const char *path)
{
    auth_keyring ring;
    char err[600];
    if (auth_keys_load(path, &ring, err, sizeof err)) {
        fprintf(stderr, "auv-auth-probe: %s\n", err);
        return 1;
    }
    for (size_t i = 0; i < ring.n; i++)
        printf("%s%s\n", ring.keys[i].id, i + 1 == ring.n ? " (signs)" : "");
    auth_keys_clear(&ring);
    return 0;
}

enum { BIG = 1 << 16 };

static int vector_line(char *line, int lineno)
{
    static uint8_t key[BIG], data[BIG], want[BIG];
    static char k[2 * 1024 + 1], d[2 * BIG + 1];
    char kind[16], w[130];
    unsigned long counter = 0;
    size_t kl, dl, wl;
    if (sscanf(line, "%15s", kind) != 1 || kind[0] == '#')
        return 0;
    if (!strcmp(kind, "hmac") && sscanf(line, "%*s %2048s %131072s %129s", k, d, w) == 3) {
        uint8_t mac[AUTH_MAC_BYTES];
        kl = unhex(k, key, sizeof key), dl = unhex(d, data, sizeof data), wl = unhex(w, want, sizeof want);
        if (kl == (size_t)-1 || dl == (size_t)-1 || wl != AUTH_MAC_BYTES)
            goto bad;
        auth_hmac_sha256(key, kl, data, dl, mac);
        if (memcmp(mac, want, AUTH_MAC_BYTES)) {
            printf("line %d: hmac differs\n", lineno);
            return 1;
        }
        return 0;
    }
    if (!strcmp(kind, "acoustic") && sscanf(line, "%*s %2048s %lu %131072s %129s", k, &counter, d, w) == 4) {
        uint32_t tag;
        kl = unhex(k, key, sizeof key), dl = unhex(strcmp(d, "-") ? d : "", data, sizeof data);
        if (kl == (size_t)-1 || dl == (size_t)-1 || auth_acoustic_tag(key, kl, data, dl, (uint32_t)counter, &tag))
            goto bad;
        if (tag != (uint32_t)strtoul(w, NULL, 16)) {
            printf("line %d: acoustic tag %08" PRIx32 ", the vector says %s\n", lineno, tag, w);
            return 1;
        }
        return 0;
    }
bad:
    printf("line %d: not a vector line\n", lineno);
    return 1;
}

static int cmd_vectors(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        perror(path);
        return 2;
    }
    static char line[2 * BIG + 4096];
    int lineno = 0, bad = 0, n = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        int b = vector_line(line, lineno);
        bad += b;
        n += !b && line[0] != '#' && line[0] != '\n';
    }
    fclose(f);
    if (!bad)
        printf("ok %d\n", n);
    return bad ? 1 : 0;
}

/* Decoded as the managers do (rx_decode: validated first, nothing leaked on
 * a message cut short), then verified. */
static auth_result offer(auth_verifier *v, const unsigned char *buf, size_t len, int64_t now_us, int *undecodable)
{
    auv_mission_command_t c;
    auv_plugin_upload_t u;
    auth_result r = AUTH_BAD_MAC;
    *undecodable = 0;
    if (rx_decode(auv_type_find("mission_command_t"), buf, (int)len, &c) == 0) {
        r = auth_verify_mission_command(v, &c, now_us);
        auv_mission_command_t_decode_cleanup(&c);
    } else if (rx_decode(auv_type_find("plugin_upload_t"), buf, (int)len, &u) == 0) {
        r = auth_verify_plugin_upload(v, &u, now_us);
        auv_plugin_upload_t_decode_cleanup(&u);
    } else {
        *undecodable = 1;
    }
    return r;
}

static int cmd_verify(int argc, char **argv)
{
    static auth_verifier v;
    char err[600];
    if (auth_keys_load(argv[2], &v.ring, err, sizeof err)) {
        fprintf(stderr, "auv-auth-probe: %s\n", err);
        return 1;
    }
    int64_t now = strtoll(argv[3], NULL, 10);
    for (int i = 4; i < argc; i++) {
        size_t len;
        unsigned char *buf = read_all(argv[i], &len);
        int undecodable;
        if (!buf) {
            perror(argv[i]);
            return 2;
        }
        auth_result r = offer(&v, buf, len, now, &undecodable);
        printf("%s\n", undecodable ? "undecodable" : auth_result_name(r));
        free(buf);
    }
    auth_keys_clear(&v.ring);
    return 0;
}

static int cmd_acoustic(int argc, char **argv)
{
    static uint8_t key[AUTH_MAX_SECRET], payload[AUTH_ACOUSTIC_MAX_PAYLOAD];
    size_t kl = unhex(argv[2], key, sizeof key);
    if (kl == (size_t)-1)
        return 2;
    auth_acoustic_window w;
    auth_acoustic_init(&w);
    for (int i = 3; i < argc; i++) {
        char hex[2 * AUTH_ACOUSTIC_MAX_PAYLOAD + 1] = "";
        unsigned long counter;
        unsigned tag;
        if (sscanf(argv[i], "%lu:%512[0-9a-fA-F]:%x", &counter, hex, &tag) != 3 &&
            sscanf(argv[i], "%lu::%x", &counter, &tag) != 2)
            return 2;
        size_t n = unhex(hex, payload, sizeof payload);
        if (n == (size_t)-1)
            return 2;
        printf("%d\n", auth_acoustic_verify(&w, key, kl, payload, n, (uint32_t)counter, (uint32_t)tag));
    }
    return 0;
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int cmd_bench(const char *keyfile, const char *path, long n)
{
    static auth_verifier v;
    char err[600];
    size_t len;
    unsigned char *buf = read_all(path, &len);
    if (!buf || n <= 0 || auth_keys_load(keyfile, &v.ring, err, sizeof err)) {
        fprintf(stderr, "auv-auth-probe: bench: %s\n", buf ? err : path);
        free(buf);
        return 2;
    }
    auv_mission_command_t c;
    int bad = 0;
    double t0 = now_ns();
    for (long i = 0; i < n; i++) {
        bad |= auv_mission_command_t_decode(buf, 0, (int)len, &c) != (int)len;
        auv_mission_command_t_decode_cleanup(&c);
    }
    double t1 = now_ns();
    for (long i = 0; i < n; i++) {
        v.n_peers = 0; /* the same message each time: not a replay for this measure */
        bad |= auv_mission_command_t_decode(buf, 0, (int)len, &c) != (int)len;
        bad |= auth_verify_mission_command(&v, &c, c.auth.counter) != AUTH_OK;
        auv_mission_command_t_decode_cleanup(&c);
    }
    double t2 = now_ns();
    printf("bytes %zu decode_ns %.0f decode_verify_ns %.0f%s\n", len, (t1 - t0) / (double)n, (t2 - t1) / (double)n,
           bad ? " FAILED" : "");
    free(buf);
    auth_keys_clear(&v.ring);
    return bad;
}

int main(int argc, char **argv)
{
    if (argc == 5 && !strcmp(argv[1], "bench"))
        return cmd_bench(argv[2], argv[3], atol(argv[4]));
    if (argc == 3 && !strcmp(argv[1], "keys"))
        return cmd_keys(argv[2]);
    if (argc == 3 && !strcmp(argv[1], "vectors"))
        return cmd_vectors(argv[2]);
    if (argc >= 4 && !strcmp(argv[1], "verify"))
        return cmd_verify(argc, argv);
    if (argc >= 3 && !strcmp(argv[1], "acoustic"))
        return cmd_acoustic(argc, argv);
    fprintf(argc > 1 && !strcmp(argv[1], "--help") ? stdout : stderr,
            "usage: auv-auth-probe keys FILE | vectors FILE | verify KEYFILE NOW_US MSGFILE... |\n"
            "       acoustic KEYHEX COUNTER:PAYLOADHEX:TAGHEX... | bench KEYFILE MSGFILE N\n");
    return argc > 1 && !strcmp(argv[1], "--help") ? 0 : 2;
}
