/* test_basic built for a newer plugin ABI (100): loading or hot-plugging it
 * must fail. test_basic_abi2.c is the older side. */
#define TEST_GAIN 3
#include "test_basic_impl.h"
/* Written out rather than CHASM_PLUGIN_EXPORT, which always says CHASM_PLUGIN_ABI. */
__attribute__((visibility("default"))) const chasm_plugin_descriptor chasm_plugin = {
    .abi_version = 100, .struct_size = sizeof(chasm_plugin_descriptor), .name = "test_basic", .version = "9.0.0",
    CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests)};
