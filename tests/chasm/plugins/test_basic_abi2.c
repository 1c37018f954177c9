/* test_basic as built against chasm_plugin.h of ABI 2 (before flags and
 * param_given): the descriptor says 2, so loading or hot-plugging it must
 * fail with the reason, before anything of its tables is read. */
#define TEST_GAIN 4
#include "test_basic_impl.h"
__attribute__((visibility("default"))) const chasm_plugin_descriptor chasm_plugin = {
    2, sizeof(chasm_plugin_descriptor), "test_basic", "2.9.0",
    behaviors, CHASM_COUNT(behaviors), tests, CHASM_COUNT(tests)};
