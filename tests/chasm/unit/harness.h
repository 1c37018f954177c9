/* Tiny test harness for the C unit tests of libchasm: each test is a
 * function; `chasm_unit_tests NAME` runs one, no argument runs all. The
 * plugin folder comes from --plugins DIR. */
#ifndef CHASM_HARNESS_H
#define CHASM_HARNESS_H
#include <stdio.h>
#include <string.h>

#include "chasm/chasm.h"

extern const char *plugin_dir;
extern int failures;
extern long alloc_count; /* allocations so far (malloc, calloc, realloc) */
extern char logbuf[65536];

#define CHECK(cond)                                                                     \
    do {                                                                                \
        if (!(cond)) {                                                                  \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);    \
            failures++;                                                                 \
        }                                                                               \
    } while (0)
#define CHECK_STR(a, b)                                                                           \
    do {                                                                                          \
        const char *a_ = (a), *b_ = (b);                                                          \
        if (strcmp(a_ ? a_ : "(null)", b_)) {                                                     \
            fprintf(stderr, "%s:%d: expected \"%s\", got \"%s\"\n", __FILE__, __LINE__, b_, a_ ? a_ : "(null)"); \
            failures++;                                                                           \
        }                                                                                         \
    } while (0)

/* Loads a plan given as text (plugins from plugin_dir); prints errors, NULL on failure. */
chasm_machine *load_plan(const char *text);
/* Loads and returns the first error line, "" if it loaded. Caller frees nothing. */
const char *first_error(const char *text);
/* The leaf path of the active path. */
const char *leaf(chasm_machine *m);
/* Steps at 100 ms from t0 (s) to t1 (s) inclusive; returns the final run state. */
chasm_run_state run_until(chasm_machine *m, double t0, double t1);
void set_d(chasm_machine *m, const char *var, double v, double t_s);
void set_b(chasm_machine *m, const char *var, int v, double t_s);
double get_d(chasm_machine *m, const char *var);
int64_t get_i(chasm_machine *m, const char *var);
void log_clear(void);

typedef struct {
    const char *name;
    void (*fn)(void);
} unit_test;
#endif
