/* A small mutation fuzzer for machines without libFuzzer (gcc only): reads a
 * corpus, mutates entries (bit flips, byte edits, block copies, dictionary
 * words of the plan language, splices, interesting integers written over
 * header-sized fields, truncation) and feeds LLVMFuzzerTestOneInput. It drives
 * both the plan fuzzer and the plugin-file fuzzer (--no-dict: binary input).
 * Built with ASan+UBSan, a crash aborts; the input that caused it is written
 * to ./chasm-crash-<seed>.chasm first. Deterministic for a given --seed.
 *
 *   chasm_fuzz [--seconds N] [--runs N] [--seed N] [--no-dict] CORPUS_DIR_OR_FILE... */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
extern void __sanitizer_set_death_callback(void (*)(void)) __attribute__((weak));

typedef struct {
    uint8_t *d;
    size_t n;
} buf_t;

#define FUZZ_MAX_INPUT (1024 * 1024) /* a plan, or a plugin file */
static buf_t corpus[4096];
static size_t n_corpus;
static int use_dict = 1;
static uint8_t cur[FUZZ_MAX_INPUT];
static size_t cur_n;
static unsigned long long seed_arg;

static uint64_t rng_state;
static uint64_t rnd(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}

static const char *dict[] = {
    "state ", "start ", "next ", "when ", "-> ", "do ", "set ", "test ", "param ", "use ", "input ", "output ",
    "var ", "abort when ", "include \"x\"", "on entry", "on exit", "every cycle", "every 2 s", "after 3 s",
    "for 5 s", "within 1 m of ", "tolerance ", "age ", "elapsed > 1 s", " and ", " or ", "not ", "(", ")", "{",
    "}\n", "\n", "resume ", "resume deep ", "done", "failed", "true", "false", "$p", " m", " s", " deg", " m/s",
    "== ", "!= ", "<= ", ">= ", "< ", "> ", "= ", ": double m", ": int", ": bool", ": string", "\"", "#", "/", ",",
    "1e308", "-0", "0.5", "99999999999999999999", "nav.depth", "a.b.c",
    /* binding files (c/managers/fuzz/fuzz_bindings.c uses this driver too) */
    "input nav ", "output setpoint ", "${VEHICLE}", "${VEHICLE}.NAV ", " nav_solution_t", " setpoint_t",
    " gps_fix_t", " optional", "\t", "\r\n"};

static void load_path(const char *p)
{
    DIR *dir = opendir(p);
    if (dir) {
        struct dirent *e;
        while ((e = readdir(dir))) {
            if (e->d_name[0] == '.') continue;
            char q[4096];
            snprintf(q, sizeof q, "%s/%s", p, e->d_name);
            load_path(q);
        }
        closedir(dir);
        return;
    }
    FILE *f = fopen(p, "rb");
    if (!f || n_corpus >= 4096) {
        if (f) fclose(f);
        return;
    }
    buf_t b = {malloc(FUZZ_MAX_INPUT), 0};
    if (!b.d) abort();
    b.n = fread(b.d, 1, FUZZ_MAX_INPUT, f);
    fclose(f);
    corpus[n_corpus++] = b;
}

static void insert(size_t at, const uint8_t *src, size_t len)
{
    if (cur_n + len > sizeof cur) return;
    memmove(cur + at + len, cur + at, cur_n - at);
    memcpy(cur + at, src, len);
    cur_n += len;
}

static void mutate(void)
{
    int n = 1 + (int)(rnd() % 6);
    for (int k = 0; k < n; k++) {
        size_t at = cur_n ? rnd() % (cur_n + 1) : 0;
        switch (rnd() % 9) {
        case 0:
            if (cur_n) cur[rnd() % cur_n] ^= (uint8_t)(1u << (rnd() % 8));
            break;
        case 1:
            if (cur_n) cur[rnd() % cur_n] = (uint8_t)rnd();
            break;
        case 2: { /* delete a block */
            if (!cur_n) break;
            size_t len = 1 + rnd() % 16;
            if (at + len > cur_n) len = cur_n - at;
            memmove(cur + at, cur + at + len, cur_n - at - len);
            cur_n -= len;
            break;
        }
        case 3: { /* duplicate a block */
            if (!cur_n) break;
            size_t from = rnd() % cur_n, len = 1 + rnd() % 64;
            if (from + len > cur_n) len = cur_n - from;
            uint8_t tmp[64];
            memcpy(tmp, cur + from, len);
            insert(at, tmp, len);
            break;
        }
        case 8: { /* an interesting integer over a field, mostly in the headers */
            static const uint64_t vals[] = {0, 1, 2, 0x7f, 0x80, 0xff, 0x100, 0x7fff, 0xffff, 0x7fffffff,
                                            0x80000000u, 0xffffffffu, 0x7fffffffffffffffull, ~0ull};
            size_t w = (size_t)1 << (rnd() % 4);
            if (cur_n < w) break;
            size_t span = rnd() % 2 && cur_n > 4096 ? 4096 : cur_n;
            size_t off = rnd() % (span - w + 1);
            uint64_t v = rnd() % 4 == 0 ? (uint64_t)cur_n + rnd() % 64 : vals[rnd() % (sizeof vals / sizeof vals[0])];
            memcpy(cur + off, &v, w); /* little-endian hosts: the low bytes */
            break;
        }
        case 4:
        case 5: {
            if (!use_dict) break;
            const char *w = dict[rnd() % (sizeof dict / sizeof dict[0])];
            insert(at, (const uint8_t *)w, strlen(w));
            break;
        }
        case 6: { /* splice from another entry */
            const buf_t *o = &corpus[rnd() % n_corpus];
            if (!o->n) break;
            size_t from = rnd() % o->n, len = 1 + rnd() % 256;
            if (from + len > o->n) len = o->n - from;
            insert(at, o->d + from, len);
            break;
        }
        case 7: { /* swap two lines' worth of bytes by truncating */
            if (cur_n && rnd() % 4 == 0) cur_n = at;
            break;
        }
        }
    }
}

static pid_t main_pid;

static void on_death(void)
{
    if (getpid() != main_pid) return; /* a child the target forked (the plugin probe) */
    char name[64];
    snprintf(name, sizeof name, "chasm-crash-%llu.chasm", seed_arg);
    FILE *f = fopen(name, "wb");
    if (f) {
        fwrite(cur, 1, cur_n, f);
        fclose(f);
        fprintf(stderr, "chasm_fuzz: crashing input written to %s\n", name);
    }
}

int main(int argc, char **argv)
{
    double seconds = 10;
    long long runs = -1;
    seed_arg = 1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--seconds") && i + 1 < argc) seconds = atof(argv[++i]);
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc) runs = atoll(argv[++i]);
        else if (!strcmp(argv[i], "--seed") && i + 1 < argc) seed_arg = strtoull(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--no-dict")) use_dict = 0;
        else load_path(argv[i]);
    }
    if (!n_corpus) {
        fputs("chasm_fuzz: no corpus files\n", stderr);
        return 2;
    }
    main_pid = getpid();
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(on_death);
    rng_state = seed_arg * 0x9E3779B97F4A7C15ull + 1;
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    long long n = 0;
    /* every corpus entry once, unmutated */
    for (size_t i = 0; i < n_corpus; i++, n++) {
        memcpy(cur, corpus[i].d, corpus[i].n);
        cur_n = corpus[i].n;
        LLVMFuzzerTestOneInput(cur, cur_n);
    }
    double el = 0;
    for (;; n++) {
        if (runs >= 0 && n >= runs) break;
        if ((n & 31) == 0) {
            clock_gettime(CLOCK_MONOTONIC, &t);
            el = (double)(t.tv_sec - t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - t0.tv_nsec);
            if (runs < 0 && el >= seconds) break;
        }
        const buf_t *b = &corpus[rnd() % n_corpus];
        memcpy(cur, b->d, b->n);
        cur_n = b->n;
        mutate();
        LLVMFuzzerTestOneInput(cur, cur_n);
    }
    clock_gettime(CLOCK_MONOTONIC, &t);
    el = (double)(t.tv_sec - t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - t0.tv_nsec);
    printf("chasm_fuzz: %lld inputs in %.1f s (%.0f/s), corpus %zu, seed %llu, no crash\n", n, el, (double)n / (el > 0 ? el : 1),
           n_corpus, seed_arg);
    for (size_t i = 0; i < n_corpus; i++) free(corpus[i].d);
    return 0;
}
