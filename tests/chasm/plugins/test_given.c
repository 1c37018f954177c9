/* chasm_param_given: `probe` writes whether each of its slots was given (an
 * optional parameter without a default, one with a default, an optional
 * input) and the optional value; the test handler `has_opt` is true when
 * opt was given; the check refuses opt = 13 m, and only when given. */
#include <stdio.h>
#include <string.h>

#include "chasm/chasm_plugin.h"

enum { OPT, DEF, IN, OPT_GIVEN, DEF_GIVEN, IN_GIVEN, OPT_VALUE, NPARAMS };
static const chasm_param_spec params[NPARAMS] = {
    [OPT] = CHASM_PARAM_OPTIONAL_RANGE("opt", CHASM_DOUBLE, "m", 0, 100, "optional, no default"),
    [DEF] = CHASM_PARAM_DOUBLE("def", "m", 5, "optional, default 5 m"),
    [IN] = CHASM_READ("in", CHASM_DOUBLE, "m", NULL, "an input the plan may bind"),
    [OPT_GIVEN] = CHASM_WRITE("opt_given", CHASM_BOOL, "", "test.opt_given", NULL),
    [DEF_GIVEN] = CHASM_WRITE("def_given", CHASM_BOOL, "", "test.def_given", NULL),
    [IN_GIVEN] = CHASM_WRITE("in_given", CHASM_BOOL, "", "test.in_given", NULL),
    [OPT_VALUE] = CHASM_WRITE("opt_value", CHASM_DOUBLE, "m", "test.opt_value", NULL),
};
static chasm_status_code step(chasm_ctx *c, void *s)
{
    (void)s;
    chasm_write_bool(c, OPT_GIVEN, chasm_param_given(c, OPT));
    chasm_write_bool(c, DEF_GIVEN, chasm_param_given(c, DEF));
    chasm_write_bool(c, IN_GIVEN, chasm_param_given(c, IN));
    chasm_write_double(c, OPT_VALUE, chasm_param_double(c, OPT));
    return CHASM_RUNNING;
}
static const chasm_behavior_spec behaviors[] = {
    {.name = "probe", .doc = "writes what was given", CHASM_SCHEMA(params), .step = step},
};

static const chasm_param_spec test_params[] = {
    [OPT] = CHASM_PARAM_OPTIONAL("opt", CHASM_DOUBLE, "m", NULL),
};
static int has_opt(chasm_ctx *c) { return chasm_param_given(c, OPT); }
static const chasm_test_spec tests[] = {
    {.name = "has_opt", .doc = "opt was given", CHASM_SCHEMA(test_params), .evaluate = has_opt},
};
CHASM_PLUGIN_EXPORT("test_given", "1.0.0", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));

CHASM_PLUGIN_CHECK(check)
static int check(const char *item, const chasm_ctx *c, int *slot, char *why, size_t whylen)
{
    (void)item; /* both keep opt in slot OPT */
    if (!chasm_param_given(c, OPT) || chasm_param_double(c, OPT) != 13.0) return 0;
    *slot = OPT;
    snprintf(why, whylen, "13 m is unlucky");
    return 1;
}
