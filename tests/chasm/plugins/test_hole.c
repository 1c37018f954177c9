/* A schema indexed by its slot enum with one slot left out: the table has a
 * hole (an entry with no name) that the loader must refuse, naming the
 * plugin, the behavior and the slot. */
#include "chasm/chasm_plugin.h"

enum { A, B, C, NPARAMS };
static const chasm_param_spec params[NPARAMS] = {
    [A] = CHASM_PARAM_DOUBLE("a", "m", 1, NULL),
    [C] = CHASM_PARAM_DOUBLE("c", "m", 3, NULL),
};
static chasm_status_code step(chasm_ctx *c, void *s) { (void)c; (void)s; return CHASM_RUNNING; }
static const chasm_behavior_spec behaviors[] = {
    {.name = "holey", .doc = "a table with a hole", CHASM_SCHEMA(params), .step = step},
};
CHASM_PLUGIN_EXPORT("test_hole", "1.0.0", CHASM_BEHAVIORS(behaviors));
