/* A second plugin with a behavior named like one of test_basic's (hold), to
 * test ambiguity, and a typed parameter set for schema checks. */
#include "chasm/chasm_plugin.h"
static chasm_status_code step(chasm_ctx *c, void *s) { (void)c; (void)s; return CHASM_RUNNING; }
static const chasm_param_spec goto_params[] = {
    CHASM_PARAM_REQUIRED_DOUBLE("north", "m", NULL),
    CHASM_PARAM_DOUBLE_RANGE("speed", "m/s", 1.0, 0.2, 2.5, NULL),
    CHASM_WRITE("heading", CHASM_DOUBLE, "rad", "setpoint.heading", NULL),
    CHASM_PARAM_STRING("label", "leg", NULL),
    CHASM_PARAM_INT("loops", 1, NULL),
    CHASM_PARAM_BOOL("verbose", 0, NULL),
};
static const chasm_behavior_spec behaviors[] = {
    {.name = "hold", .step = step},
    {.name = "goto", CHASM_SCHEMA(goto_params), .step = step},
};
CHASM_PLUGIN_EXPORT("test_other", "1.0.0", CHASM_BEHAVIORS(behaviors));
