/* A test handler that asks for messages: refused when the plugin loads (a
 * test evaluates, it must not consume a stream). */
#include "chasm/chasm_plugin.h"

static const chasm_param_spec params[] = {
    CHASM_READ_REQUIRED("rx", CHASM_MESSAGES, "", "messages"),
};
static int any(chasm_ctx *c) { size_t n; return chasm_next_message(c, 0, &n) != NULL; }
static const chasm_test_spec tests[] = {
    {.name = "any_message", .doc = "true when a message came", CHASM_SCHEMA(params), .evaluate = any},
};
CHASM_PLUGIN_EXPORT("test_msgs_badtest", "1.0.0", CHASM_TESTS(tests));
