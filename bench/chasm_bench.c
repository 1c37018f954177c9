/* CHASM benchmark: load time and step cost for generated plans of 10 to
 * 10 000 states (chains up to 8 deep, 10 tests on the active path, a
 * transition per state whose condition stays false so every cycle checks
 * them all). Prints figures; asserts nothing.
 *
 *   chasm_bench [--cycles N] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "chasm/chasm.h"

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct {
    char *p;
    size_t n, cap;
    long lines;
} text_t;

static void put(text_t *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
#include <stdarg.h>
static void put(text_t *t, const char *fmt, ...)
{
    va_list ap;
    for (;;) {
        va_start(ap, fmt);
        int k = vsnprintf(t->p + t->n, t->cap - t->n, fmt, ap);
        va_end(ap);
        if ((size_t)k < t->cap - t->n) {
            t->n += (size_t)k;
            t->lines++;
            return;
        }
        t->cap = t->cap ? t->cap * 2 : 1 << 20;
        t->p = realloc(t->p, t->cap);
        if (!t->p) abort();
    }
}

/* Chains of 8 nested states; the first chain is the active path and carries
 * the 10 tests. Every state has a transition to the next chain. */
static text_t generate(int n_states)
{
    text_t t = {0};
    put(&t, "# generated: %d states\n", n_states);
    put(&t, "param limit = 100 m\n");
    put(&t, "input x : double m\ninput y : double m\noutput sp : double m\n");
    int depth = n_states < 8 ? n_states : 8;
    int chains = n_states / depth;
    int tests_left = 10;
    for (int c = 0; c < chains; c++) {
        int d = (c == chains - 1) ? n_states - c * depth : depth;
        for (int k = 0; k < d; k++) {
            put(&t, "%*sstate s%d_%d {\n", 2 * k, "", c, k);
            int nt = c == 0 ? (k < 2 ? 2 : 1) : 1;
            if (c == 0 && k == d - 1) nt = tests_left;
            if (c == 0) {
                if (nt > tests_left) nt = tests_left;
                tests_left -= nt;
            }
            for (int i = 0; i < nt; i++)
                put(&t, "%*s  test t%d : x > $limit tolerance 0.5 m for 2 s  # never true here\n", 2 * k, "", i);
            put(&t, "%*s  when elapsed > 1 h and (t0 or not t0) -> s%d_0\n", 2 * k, "", (c + 1) % chains);
            if (k == d - 1) put(&t, "%*s  do set sp = 5 m on entry\n", 2 * k, "");
        }
        for (int k = d - 1; k >= 0; k--) put(&t, "%*s}\n", 2 * k, "");
    }
    return t;
}

int main(int argc, char **argv)
{
    long cycles = 200000;
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--cycles") && i + 1 < argc) cycles = atol(argv[++i]);
    int sizes[] = {10, 100, 1000, 10000};
    printf("%8s %8s %10s %12s %14s %14s\n", "states", "lines", "load [ms]", "lines/s", "step [ns/cyc]", "path tests");
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        text_t t = generate(sizes[s]);
        chasm_errors *e = NULL;
        int reps = sizes[s] >= 1000 ? 5 : 50;
        chasm_machine *m = NULL;
        double best = 1e9;
        for (int r = 0; r < reps; r++) {
            double t0 = now_s();
            chasm_machine *x = chasm_load_string("bench", t.p, t.n, NULL, &e);
            double dt = now_s() - t0;
            if (!x) {
                for (size_t i = 0; i < chasm_errors_count(e) && i < 5; i++) fprintf(stderr, "%s\n", chasm_errors_get(e, i));
                return 1;
            }
            if (dt < best) best = dt;
            if (m) chasm_free(m);
            m = x;
        }
        int vx = chasm_var_find(m, "x");
        chasm_start(m, 0);
        int64_t now = 0;
        for (long c = 0; c < 1000; c++) { /* warm up */
            now += 100000;
            chasm_var_set_double(m, vx, 1.0, now);
            chasm_step(m, now);
        }
        double t0 = now_s();
        for (long c = 0; c < cycles; c++) {
            now += 100000;
            chasm_var_set_double(m, vx, (double)(c & 7), now);
            chasm_step(m, now);
        }
        double step = (now_s() - t0) / (double)cycles;
        chasm_status st;
        chasm_status_get(m, now, &st);
        printf("%8d %8ld %10.3f %12.0f %14.1f %14d\n", sizes[s], t.lines, best * 1e3, (double)t.lines / best, step * 1e9,
               10);
        if (st.run_state != CHASM_RUN_RUNNING || st.path_len < 1) fprintf(stderr, "warning: machine not running\n");
        chasm_free(m);
        free(t.p);
    }
    return 0;
}
