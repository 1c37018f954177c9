/* Behaviors of the test plugin, shared by version 1 and 2 (TEST_GAIN differs
 * so a test can see which code ran). Header-only: each .so is one source. */
#include <stdio.h>
#include <string.h>

#include "chasm/chasm_plugin.h"

/* hold: writes value * TEST_GAIN to its output every time it runs; never done. */
enum { HOLD_VALUE, HOLD_OUT, HOLD_NPARAMS };
static const chasm_param_spec hold_params[HOLD_NPARAMS] = {
    [HOLD_VALUE] = CHASM_PARAM_REQUIRED_DOUBLE_RANGE("value", "m", -100, 100, "depth to hold"),
    [HOLD_OUT] = CHASM_WRITE("out", CHASM_DOUBLE, "m", "test.out", "where it goes"),
};
static chasm_status_code hold_step(chasm_ctx *c, void *st)
{
    (void)st;
    chasm_write_double(c, HOLD_OUT, chasm_param_double(c, HOLD_VALUE) * TEST_GAIN);
    return CHASM_RUNNING;
}

/* count_to: done after n steps; writes its count. */
enum { COUNT_N, COUNT_OUT, COUNT_NPARAMS };
static const chasm_param_spec count_params[COUNT_NPARAMS] = {
    [COUNT_N] = CHASM_PARAM_REQUIRED_INT_RANGE("n", 1, 1000000, "steps until done"),
    [COUNT_OUT] = CHASM_WRITE("count", CHASM_INT, "", "test.count", NULL),
};
typedef struct { int64_t k; } count_state;
static chasm_status_code count_step(chasm_ctx *c, void *st)
{
    count_state *s = st;
    s->k++;
    chasm_write_int(c, COUNT_OUT, s->k);
    return s->k >= chasm_param_int(c, COUNT_N) ? CHASM_DONE : CHASM_RUNNING;
}

/* fail_after: fails at its n-th step. */
static const chasm_param_spec fail_params[] = {
    CHASM_PARAM_INT("n", 1, NULL),
};
static chasm_status_code fail_step(chasm_ctx *c, void *st)
{
    count_state *s = st;
    return ++s->k >= chasm_param_int(c, 0) ? CHASM_FAILED : CHASM_RUNNING;
}

/* trace: logs "start TAG", "step TAG" and "stop TAG" so tests see the order. */
static const chasm_param_spec trace_params[] = {
    CHASM_PARAM_REQUIRED_STRING("tag", NULL),
};
static void trace_msg(chasm_ctx *c, const char *what)
{
    char b[160];
    snprintf(b, sizeof b, "%s %s v%d", what, chasm_param_string(c, 0), TEST_GAIN);
    chasm_log(c, b);
}
static int trace_start(chasm_ctx *c, void *st) { (void)st; trace_msg(c, "start"); return 0; }
static chasm_status_code trace_step(chasm_ctx *c, void *st) { (void)st; trace_msg(c, "step"); return CHASM_RUNNING; }
static void trace_stop(chasm_ctx *c, void *st) { (void)st; trace_msg(c, "stop"); }

static const chasm_behavior_spec behaviors[] = {
    {.name = "hold", .doc = "hold a value", CHASM_SCHEMA(hold_params), .step = hold_step},
    {.name = "count_to", .doc = "count steps", CHASM_SCHEMA(count_params), .state_size = sizeof(count_state),
     .step = count_step},
    {.name = "fail_after", .doc = "fail after n steps", CHASM_SCHEMA(fail_params), .state_size = sizeof(count_state),
     .step = fail_step},
    {.name = "trace", .doc = "log calls", CHASM_SCHEMA(trace_params), .start = trace_start, .step = trace_step,
     .stop = trace_stop},
};

/* above: true when the variable x is above limit. */
static const chasm_param_spec above_params[] = {
    CHASM_READ_REQUIRED("x", CHASM_DOUBLE, "m", NULL),
    CHASM_PARAM_REQUIRED_DOUBLE("limit", "m", NULL),
};
static int above_eval(chasm_ctx *c) { return chasm_read_double(c, 0) > chasm_param_double(c, 1); }
static const chasm_test_spec tests[] = {
    {.name = "above", .doc = "x > limit", CHASM_SCHEMA(above_params), .evaluate = above_eval},
};
