/* The checks plugin's descriptor: `use checks` loads chasm_checks.so. */
#include "plugins/checks/checks.h"

/* The descriptor wants one contiguous array; the specs live with their code
 * in the other files, so the array is filled when the plugin is loaded. */
static chasm_test_spec tests[6];

__attribute__((constructor)) static void collect(void)
{
    tests[0] = checks_depth_within;
    tests[1] = checks_altitude_within;
    tests[2] = checks_heading_within;
    tests[3] = checks_pitch_within;
    tests[4] = checks_near;
    tests[5] = checks_outside_area;
}

CHASM_PLUGIN_EXPORT("checks", "1.0.0", NULL, 0, tests, CHASM_COUNT(tests));
