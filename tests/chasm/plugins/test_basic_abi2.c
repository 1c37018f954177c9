/* test_basic as built against chasm_plugin.h of ABI 2 (before flags and
 * param_given): the descriptor says 2, so loading or hot-plugging it must
 * fail with the reason, before anything of its tables is read. */
#define TEST_GAIN 4
#include "test_basic_impl.h"
/* Written out rather than CHASM_PLUGIN_EXPORT, which always says CHASM_PLUGIN_ABI. */
__attribute__((visibility("default"))) const chasm_plugin_descriptor chasm_plugin = {
    .abi_version = 2, .struct_size = sizeof(chasm_plugin_descriptor), .name = "test_basic", .version = "2.9.0",
    CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests)};
