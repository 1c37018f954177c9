/* A plugin that is fine except that its constructor ends the process that
 * loads it (exit(3)): the probe process must end instead of the loader. */
#include <stdlib.h>
#define TEST_GAIN 1
#include "test_basic_impl.h"
__attribute__((constructor)) static void exit_on_load(void) { exit(3); }
CHASM_PLUGIN_EXPORT("test_basic", "1.0.0-exit", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));
