/* Unit tests of plugin `guidance` on the shared plugin test harness
 * (tests/plugins/common/plugin_test.h): geometry by calling the plugin's
 * functions (linked in), behaviors by loading plans that `use guidance` and
 * stepping them against a kinematic vehicle. */
#ifndef GD_TESTS_H
#define GD_TESTS_H

#include "../common/plugin_test.h"

/* The navigator's variables as missions/common/navigator_io.chasm declares
 * them, after `use guidance`. */
extern const char *const NAV_PRELUDE;
/* NAV_PRELUDE + text (prelude = 1) or "use guidance\n" + text, in a static buffer. */
const char *plan_of(const char *text, int prelude);
/* pt_load / pt_errors of plan_of(text, ...). */
chasm_machine *gd_load(const char *text);
const char *gd_errors(const char *text, int prelude);
/* Line number in NAV_PRELUDE + text of the first line of text. */
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

#define GD_TEST(name) void name(void);
#include "gd_test_names.h"
#undef GD_TEST

#endif
