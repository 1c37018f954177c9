/* A plugin that is fine except that its constructor crashes (SIGSEGV) when
 * loaded: the probe process must die instead of the loader. */
#include <signal.h>
#define TEST_GAIN 1
#include "test_basic_impl.h"
__attribute__((constructor)) static void crash_on_load(void) { raise(SIGSEGV); }
CHASM_PLUGIN_EXPORT("test_basic", "1.0.0-crash", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));
