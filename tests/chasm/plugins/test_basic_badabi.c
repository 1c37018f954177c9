/* test_basic built for another plugin ABI: loading or hot-plugging it must fail. */
#define TEST_GAIN 3
#include "test_basic_impl.h"
__attribute__((visibility("default"))) const chasm_plugin_descriptor chasm_plugin = {
    CHASM_PLUGIN_ABI + 98, sizeof(chasm_plugin_descriptor), "test_basic", "9.0.0",
    behaviors, CHASM_COUNT(behaviors), tests, CHASM_COUNT(tests)};
