/* A small harness for the C unit tests of plugins (the files in tests/plugins/NAME,
 * linked into build/bin/test_plugin_NAME with the plugin's objects, the
 * shared plugin lib and libchasm).
 *
 *   test_plugin_NAME --plugins DIR [TEST]     run one test, or all; prints "ok TEST"
 *
 * A test file defines `const plugin_test plugin_tests[]` and
 * `const size_t plugin_tests_count`. Plans are loaded with the real libchasm
 * (chasm_load_string, plugins from DIR) as "t.chasm", so errors read
 * "t.chasm:LINE:COL: error: ...". */
#ifndef PLUGIN_TEST_H
#define PLUGIN_TEST_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chasm/chasm.h"

extern int pt_failures;
extern char pt_log[8192];   /* plugin and engine log messages, each ending in ';' */

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            pt_failures++;                                                           \
        }                                                                            \
    } while (0)
/* |a - b| <= tol, printing both values when it fails. */
#define CHECK_NEAR(a, b, tol)                                                                              \
    do {                                                                                                   \
        double a_ = (a), b_ = (b);                                                                         \
        if (!(fabs(a_ - b_) <= (tol))) {                                                                   \
            fprintf(stderr, "%s:%d: %s = %.9g, expected %.9g +- %g\n", __FILE__, __LINE__, #a, a_, b_,     \
                    (double)(tol));                                                                        \
            pt_failures++;                                                                                 \
        }                                                                                                  \
    } while (0)
/* haystack contains needle. */
#define CHECK_HAS(haystack, needle)                                                                        \
    do {                                                                                                   \
        const char *h_ = (haystack), *n_ = (needle);                                                       \
        if (!h_ || !strstr(h_, n_)) {                                                                      \
            fprintf(stderr, "%s:%d: \"%s\" does not contain \"%s\"\n", __FILE__, __LINE__, h_ ? h_ : "(null)", n_); \
            pt_failures++;                                                                                 \
        }                                                                                                  \
    } while (0)

typedef struct {
    const char *name;
    void (*fn)(void);
} plugin_test;

extern const plugin_test plugin_tests[];
extern const size_t plugin_tests_count;

/* Loads a plan; prints its errors and counts a failure if it does not load. */
chasm_machine *pt_load(const char *plan);
/* All load errors, one per line ("" if the plan loaded). */
const char *pt_errors(const char *plan);
/* Blackboard access by name, times in seconds. */
void pt_set(chasm_machine *m, const char *var, double v, double t_s);
void pt_set_int(chasm_machine *m, const char *var, long v, double t_s);
double pt_get(chasm_machine *m, const char *var);
/* Starts the machine at t_s (entry actions and behavior start() run). */
void pt_start(chasm_machine *m, double t_s);
chasm_run_state pt_step(chasm_machine *m, double t_s);
/* The active leaf path. */
const char *pt_leaf(chasm_machine *m);
void pt_log_clear(void);

#endif
