/* Version 2 of test_basic, for hot plug: same schema, `hold` writes 2 * value. */
#define TEST_GAIN 2
#include "test_basic_impl.h"
CHASM_PLUGIN_EXPORT("test_basic", "2.0.0", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));
