/* A plugin that is fine except that its constructor never returns: the probe
 * process is killed after its time limit and the file refused. */
#include <unistd.h>
#define TEST_GAIN 1
#include "test_basic_impl.h"
__attribute__((constructor)) static void hang_on_load(void)
{
    for (;;) pause();
}
CHASM_PLUGIN_EXPORT("test_basic", "1.0.0-hang", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));
