/* The good test plugin, version 1. */
#define TEST_GAIN 1
#include "test_basic_impl.h"
CHASM_PLUGIN_EXPORT("test_basic", "1.0.0", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));
