/* Unit tests of plugin `guidance`: `test_plugin_guidance --plugins DIR NAME`
 * runs one test (no NAME: all). Geometry is tested by calling the plugin's
 * functions (linked in); behaviors by loading plans that `use guidance` from
 * DIR and stepping them against a kinematic vehicle. */
#ifndef GD_TEST_H
#define GD_TEST_H

#include <stdio.h>
#include <string.h>

#include "chasm/chasm.h"

extern int failures;
extern char logbuf[8192];

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (!(cond)) {                                                               \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            failures++;                                                              \
        }                                                                            \
    } while (0)
#define CHECK_NEAR(a, b, tol)                                                                              \
    do {                                                                                                   \
        double a_ = (a), b_ = (b);                                                                         \
        if (!(a_ >= b_ - (tol) && a_ <= b_ + (tol))) {                                                     \
            fprintf(stderr, "%s:%d: %s = %.6g, expected %.6g +- %g\n", __FILE__, __LINE__, #a, a_, b_, \
                    (double)(tol));                                                                        \
            failures++;                                                                                    \
        }                                                                                                  \
    } while (0)
#define CHECK_CONTAINS(text, part)                                                                 \
    do {                                                                                           \
        const char *t_ = (text), *p_ = (part);                                                     \
        if (!strstr(t_, p_)) {                                                                     \
            fprintf(stderr, "%s:%d: expected \"%s\" in \"%s\"\n", __FILE__, __LINE__, p_, t_);     \
            failures++;                                                                            \
        }                                                                                          \
    } while (0)

/* The navigator's variables as missions/common/navigator_io.chasm declares
 * them, plus `use guidance`: tests append their states to this. */
extern const char *const NAV_PRELUDE;

/* Loads PRELUDE + text named "t.chasm"; prints errors and counts a failure on NULL. */
chasm_machine *load(const char *text);
/* All load errors of PRELUDE + text (or of "use guidance\n" + text), one per
 * line ("" if it loaded). */
const char *load_errors(const char *text, int prelude);
/* Line number in PRELUDE + text of the first line of text. */
int first_line(void);

/* A kinematic vehicle: heading follows the setpoint at a limited turn rate,
 * speed through the water is constant, a uniform current adds to it. */
typedef struct {
    double n, e, psi, depth, u;
    double cur_n, cur_e;
    double max_rate; /* rad/s */
} kin_vehicle;

/* Writes v into nav.*, steps m at t seconds, then moves v by dt following the
 * heading setpoint. Returns the run state. */
chasm_run_state fly(chasm_machine *m, kin_vehicle *v, double t, double dt);
double var_d(chasm_machine *m, const char *name);
void set_var_d(chasm_machine *m, const char *name, double v, double t);
void set_var_i(chasm_machine *m, const char *name, long v, double t);
const char *leaf(chasm_machine *m);

typedef struct {
    const char *name;
    void (*fn)(void);
} unit_test;
extern const unit_test geometry_tests[], behavior_tests[];

#endif
