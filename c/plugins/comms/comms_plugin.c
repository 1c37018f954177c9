/* The descriptor of plugin `comms` (plans: `use comms`). */
#include "comms.h"

/* One table of each (chasm_plugin.h, "Registration"). */
static const chasm_behavior_spec behaviors[] = {
    {.name = "peer_report",
     .doc = "this vehicle's position, attitude and speed for the others; each run is one report "
            "(`do peer_report() every 10 s`)",
     CHASM_SCHEMA(comms_peer_report_params), .step = comms_peer_report_step},
};

static const chasm_test_spec tests[] = {
    {.name = "peer_within", .doc = "another vehicle's reported position is within radius of ours (horizontally)",
     CHASM_SCHEMA(comms_peer_within_params), .evaluate = comms_peer_within_evaluate},
};

CHASM_PLUGIN_EXPORT("comms", "1.0.0", CHASM_BEHAVIORS(behaviors), CHASM_TESTS(tests));
