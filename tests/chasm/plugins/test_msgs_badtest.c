/* A test handler that asks for messages: refused when the plugin loads (a
 * test evaluates, it must not consume a stream). */
#include "chasm/chasm_plugin.h"

static const chasm_param_spec params[] = {
    CHASM_READ_REQUIRED("rx", CHASM_MESSAGES, "", "messages"),
};
static int any(chasm_ctx *c) { size_t n; return chasm_next_message(c, 0, &n) != NULL; }
static const chasm_test_spec tests[] = {{"any_message", "true when a message came", params, 1, any}};
CHASM_PLUGIN_EXPORT("test_msgs_badtest", "1.0.0", NULL, 0, tests, CHASM_COUNT(tests));
