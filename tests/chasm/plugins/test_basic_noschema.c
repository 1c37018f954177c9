/* test_basic whose `hold` lost its `value` parameter: a hot plug of it must be
 * rejected because the running plan passes `value`. */
#include "chasm/chasm_plugin.h"
static chasm_status_code step(chasm_ctx *c, void *s) { (void)c; (void)s; return CHASM_RUNNING; }
static const chasm_behavior_spec behaviors[] = {
    {.name = "hold", .step = step},
};
CHASM_PLUGIN_EXPORT("test_basic", "4.0.0", CHASM_BEHAVIORS(behaviors));
