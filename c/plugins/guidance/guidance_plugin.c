/* Plugin `guidance`: the navigator's behaviors (docs/behaviors.md, "Navigator
 * behaviors"). Each writes pilot setpoints and reads the navigation solution
 * through variables that default to the navigator binding's fields. */
#include "gd_behaviors.h"

#define BEHAVIOR(id, name, doc, state_size, stop) \
    {name, doc, gd_##id##_params, CHASM_COUNT(gd_##id##_params), state_size, gd_##id##_start, gd_##id##_step, stop}

static const chasm_behavior_spec behaviors[] = {
    BEHAVIOR(goto, "goto", "go to a waypoint on the line from the entry position (ILOS); done within radius",
             sizeof(gd_los_state), NULL),
    BEHAVIOR(track, "track", "follow a track line (ILOS); done when past its end", sizeof(gd_los_state), NULL),
    BEHAVIOR(lawnmower, "lawnmower", "survey a box or polygon line by line; progress in a variable for resume",
             sizeof(gd_mow_state), NULL),
    BEHAVIOR(hold_depth, "hold_depth", "hold a depth", 0, NULL),
    BEHAVIOR(hold_altitude, "hold_altitude", "hold a height above the seabed (terrain following)", 0, NULL),
    BEHAVIOR(hold_heading, "hold_heading", "hold a heading", 0, NULL),
    BEHAVIOR(set_speed, "set_speed", "hold a speed through the water, or an open-loop prop rpm", 0, NULL),
    BEHAVIOR(loiter, "loiter", "station keeping on a circle around a point", 0, NULL),
    BEHAVIOR(yoyo, "yoyo", "saw-tooth between two depths or altitudes", sizeof(gd_yoyo_state), NULL),
    BEHAVIOR(surface, "surface", "float (or drive) up bow-up; done near the surface", 0, NULL),
    BEHAVIOR(surface_fix, "surface_fix", "stay at the surface until a new GPS fix; failed on timeout", 0, NULL),
    BEHAVIOR(timer, "timer", "done after a duration", 0, NULL),
};

CHASM_PLUGIN_EXPORT("guidance", "1.0.0", behaviors, CHASM_COUNT(behaviors), NULL, 0);
