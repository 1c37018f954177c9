/* A second plugin with a behavior named like one of test_basic's (hold), to
 * test ambiguity, and a typed parameter set for schema checks. */
#include "chasm/chasm_plugin.h"
static chasm_status_code step(chasm_ctx *c, void *s) { (void)c; (void)s; return CHASM_RUNNING; }
static const chasm_param_spec goto_params[] = {
    {"north", CHASM_PARAM, CHASM_DOUBLE, "m", 1, 0, NULL, 0, 0, 0, NULL},
    {"speed", CHASM_PARAM, CHASM_DOUBLE, "m/s", 0, 1.0, NULL, 1, 0.2, 2.5, NULL},
    {"heading", CHASM_WRITES, CHASM_DOUBLE, "rad", 0, 0, "setpoint.heading", 0, 0, 0, NULL},
    {"label", CHASM_PARAM, CHASM_STRING, "", 0, 0, "leg", 0, 0, 0, NULL},
    {"loops", CHASM_PARAM, CHASM_INT, "", 0, 1, NULL, 0, 0, 0, NULL},
    {"verbose", CHASM_PARAM, CHASM_BOOL, "", 0, 0, NULL, 0, 0, 0, NULL},
};
static const chasm_behavior_spec behaviors[] = {
    {"hold", NULL, NULL, 0, 0, NULL, step, NULL},
    {"goto", NULL, goto_params, CHASM_COUNT(goto_params), 0, NULL, step, NULL},
};
CHASM_PLUGIN_EXPORT("test_other", "1.0.0", behaviors, CHASM_COUNT(behaviors), NULL, 0);
