/* Plan-test helpers (pt_) on the unit harness (unit.h), for the tests that
 * load plans with the real libchasm: libchasm's own (tests/chasm/unit) and
 * the plugins' (tests/plugins/NAME). Plans are loaded as "t.chasm", so errors
 * read "t.chasm:LINE:COL: error: ...", with plugins from --plugins DIR. Times
 * are in seconds, rounded to the nearest microsecond. A helper that cannot do
 * what it is asked (no such variable, a value refused) counts a failure. */
#ifndef PLAN_TEST_H
#define PLAN_TEST_H

#include <math.h>
#include <stdint.h>

#include "chasm/chasm.h"
#include "unit.h"

/* Plugin and engine log messages since the test began, each ending in ';'. */
extern char pt_log[65536];
void pt_log_clear(void);

/* Loads a plan; prints its errors and counts a failure if it does not load. */
chasm_machine *pt_load(const char *plan);
/* All load errors, one per line ("" if the plan loaded), in a static buffer. */
const char *pt_errors(const char *plan);
/* The first load error only, without its newline ("" if the plan loaded). */
const char *pt_first_error(const char *plan);

/* Blackboard access by name. */
void pt_set(chasm_machine *m, const char *var, double v, double t_s);
void pt_set_bool(chasm_machine *m, const char *var, int v, double t_s);
void pt_set_int(chasm_machine *m, const char *var, long v, double t_s);
double pt_get(chasm_machine *m, const char *var);
int64_t pt_get_int(chasm_machine *m, const char *var);

/* Starts the machine at t_s (entry actions and behavior start() run). */
void pt_start(chasm_machine *m, double t_s);
chasm_run_state pt_step(chasm_machine *m, double t_s);
/* Steps every 100 ms from t0 to t1 inclusive while it runs; the run state. */
chasm_run_state pt_run_until(chasm_machine *m, double t0_s, double t1_s);
/* The active leaf path. */
const char *pt_leaf(chasm_machine *m);

#endif
