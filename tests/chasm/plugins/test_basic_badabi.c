/* test_basic built for a newer plugin ABI (100): loading or hot-plugging it
 * must fail. test_basic_abi2.c is the older side. */
#define TEST_GAIN 3
#include "test_basic_impl.h"
__attribute__((visibility("default"))) const chasm_plugin_descriptor chasm_plugin = {
    100, sizeof(chasm_plugin_descriptor), "test_basic", "9.0.0",
    behaviors, CHASM_COUNT(behaviors), tests, CHASM_COUNT(tests)};
