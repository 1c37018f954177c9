/* The pilot plugin's descriptor: `use pilot` in a plan loads chasm_pilot.so. */
#include <stdio.h>

#include "plugins/pilot/pilot.h"

int pilot_reject(chasm_ctx *c, const char *behavior, const char *reason)
{
    char msg[256];
    snprintf(msg, sizeof msg, "%s: %s", behavior, reason);
    chasm_log(c, msg);
    return -1;
}

/* One table (chasm_plugin.h, "Registration"); each behavior's slots, state
 * and entry points are declared in pilot.h. */
static const chasm_behavior_spec behaviors[] = {
    {.name = "heading_control",
     .doc = "hold setpoint heading with the rudder (PD with yaw-rate damping, turn-rate limit)",
     CHASM_SCHEMA(pilot_heading_control_params), .state_size = sizeof(pilot_heading_state),
     .start = pilot_heading_control_start, .step = pilot_heading_control_step},
    {.name = "depth_control", .doc = "hold setpoint depth: depth error -> pitch command -> stern plane (cascade)",
     CHASM_SCHEMA(pilot_depth_control_params), .state_size = sizeof(pilot_depth_state),
     .start = pilot_depth_control_start, .step = pilot_depth_control_step},
    {.name = "altitude_control",
     .doc = "hold setpoint altitude above the seabed (terrain following through the depth loop)",
     CHASM_SCHEMA(pilot_altitude_control_params), .state_size = sizeof(pilot_altitude_state),
     .start = pilot_altitude_control_start, .step = pilot_altitude_control_step},
    {.name = "pitch_control", .doc = "hold setpoint pitch with the stern plane (PID with pitch-rate damping)",
     CHASM_SCHEMA(pilot_pitch_control_params), .state_size = sizeof(pilot_pitch_state),
     .start = pilot_pitch_control_start, .step = pilot_pitch_control_step},
    {.name = "speed_control", .doc = "hold setpoint speed with the prop (feed-forward + PI)",
     CHASM_SCHEMA(pilot_speed_control_params), .state_size = sizeof(pilot_prop_state),
     .start = pilot_speed_control_start, .step = pilot_speed_control_step},
    {.name = "rpm_control", .doc = "drive the prop at setpoint rpm (open loop, limited and slew-limited)",
     CHASM_SCHEMA(pilot_rpm_control_params), .state_size = sizeof(pilot_prop_state),
     .start = pilot_rpm_control_start, .step = pilot_rpm_control_step},
    {.name = "setpoint_watch",
     .doc = "report the pilot's state and count the setpoints it ignores (zero or stale utime)",
     CHASM_SCHEMA(pilot_setpoint_watch_params), .state_size = sizeof(pilot_watch_state),
     .step = pilot_setpoint_watch_step},
};

CHASM_PLUGIN_EXPORT("pilot", "1.0.0", CHASM_BEHAVIORS(behaviors));
