/* The checks plugin's descriptor: `use checks` loads chasm_checks.so. */
#include "plugins/checks/checks.h"

/* One table (chasm_plugin.h, "Registration"); each handler's schema and
 * evaluate() are declared in checks.h. */
static const chasm_test_spec tests[] = {
    {.name = "depth_within", .doc = "depth within tolerance of value", CHASM_SCHEMA(checks_depth_within_params),
     .evaluate = checks_depth_within_evaluate},
    {.name = "altitude_within", .doc = "altitude within tolerance of value (false while unknown)",
     CHASM_SCHEMA(checks_altitude_within_params), .evaluate = checks_altitude_within_evaluate},
    {.name = "heading_within", .doc = "heading within tolerance of value, the short way round",
     CHASM_SCHEMA(checks_heading_within_params), .evaluate = checks_heading_within_evaluate},
    {.name = "pitch_within", .doc = "pitch within tolerance of value", CHASM_SCHEMA(checks_pitch_within_params),
     .evaluate = checks_pitch_within_evaluate},
    {.name = "near", .doc = "within radius of a point (horizontal distance)", CHASM_SCHEMA(checks_near_params),
     .evaluate = checks_near_evaluate},
    {.name = "outside_area", .doc = "outside an operating area (polygon or box), or within margin of its edge",
     CHASM_SCHEMA(checks_outside_area_params), .evaluate = checks_outside_area_evaluate},
};

CHASM_PLUGIN_EXPORT("checks", "1.0.0", CHASM_TESTS(tests));
