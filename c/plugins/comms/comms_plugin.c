/* The descriptor of plugin `comms` (plans: `use comms`). */
#include "comms.h"

static const chasm_behavior_spec behaviors[] = {
    {"peer_report",
     "this vehicle's position, attitude and speed for the others; each run is one report "
     "(`do peer_report() every 10 s`)",
     comms_peer_report_params, PR_N_SLOTS, 0, NULL, comms_peer_report_step, NULL},
};

static const chasm_test_spec tests[] = {
    {"peer_within", "another vehicle's reported position is within radius of ours (horizontally)",
     comms_peer_within_params, PW_N_SLOTS, comms_peer_within_evaluate},
};

CHASM_PLUGIN_EXPORT("comms", "1.0.0", behaviors, CHASM_COUNT(behaviors), tests, CHASM_COUNT(tests));
