/* Plugin `guidance`: the navigator's behaviors (docs/behaviors.md, "Navigator
 * behaviors"). Each writes pilot setpoints and reads the navigation solution
 * through variables that default to the navigator binding's fields. */
#include "gd_behaviors.h"

/* The behaviors, one table (chasm_plugin.h, "Registration"); each behavior's
 * schema and entry points are declared in gd_behaviors.h. */
static const chasm_behavior_spec behaviors[] = {
    {.name = "goto", .doc = "go to a waypoint on the line from the entry position (ILOS); done within radius",
     CHASM_SCHEMA(gd_goto_params), .state_size = sizeof(gd_los_state), .start = gd_goto_start, .step = gd_goto_step},
    {.name = "track", .doc = "follow a track line (ILOS); done when past its end", CHASM_SCHEMA(gd_track_params),
     .state_size = sizeof(gd_los_state), .start = gd_track_start, .step = gd_track_step},
    {.name = "lawnmower", .doc = "survey a box or polygon line by line; progress in a variable for resume",
     CHASM_SCHEMA(gd_lawnmower_params), .state_size = sizeof(gd_mow_state), .start = gd_lawnmower_start,
     .step = gd_lawnmower_step},
    {.name = "hold_depth", .doc = "hold a depth", CHASM_SCHEMA(gd_hold_depth_params), .start = gd_hold_depth_start,
     .step = gd_hold_depth_step},
    {.name = "hold_altitude", .doc = "hold a height above the seabed (terrain following)",
     CHASM_SCHEMA(gd_hold_altitude_params), .start = gd_hold_altitude_start, .step = gd_hold_altitude_step},
    {.name = "hold_heading", .doc = "hold a heading", CHASM_SCHEMA(gd_hold_heading_params),
     .start = gd_hold_heading_start, .step = gd_hold_heading_step},
    {.name = "set_speed", .doc = "hold a speed through the water, or an open-loop prop rpm",
     CHASM_SCHEMA(gd_set_speed_params), .start = gd_set_speed_start, .step = gd_set_speed_step},
    {.name = "loiter", .doc = "station keeping on a circle around a point", CHASM_SCHEMA(gd_loiter_params),
     .start = gd_loiter_start, .step = gd_loiter_step},
    {.name = "yoyo", .doc = "saw-tooth between two depths or altitudes", CHASM_SCHEMA(gd_yoyo_params),
     .state_size = sizeof(gd_yoyo_state), .start = gd_yoyo_start, .step = gd_yoyo_step},
    {.name = "front_zigzag",
     .doc = "legs at +-angle to a course across a front, turning once the temperature says it was crossed",
     CHASM_SCHEMA(gd_front_zigzag_params), .state_size = sizeof(gd_zz_state), .start = gd_front_zigzag_start,
     .step = gd_front_zigzag_step},
    {.name = "surface", .doc = "float (or drive) up bow-up; done near the surface", CHASM_SCHEMA(gd_surface_params),
     .start = gd_surface_start, .step = gd_surface_step},
    {.name = "surface_fix", .doc = "stay at the surface until a new GPS fix; failed on timeout",
     CHASM_SCHEMA(gd_surface_fix_params), .start = gd_surface_fix_start, .step = gd_surface_fix_step},
    {.name = "timer", .doc = "done after a duration", CHASM_SCHEMA(gd_timer_params), .start = gd_timer_start,
     .step = gd_timer_step},
};

CHASM_PLUGIN_EXPORT("guidance", "1.0.0", CHASM_BEHAVIORS(behaviors));
