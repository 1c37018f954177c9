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

/* The descriptor wants a contiguous array; the specs live with their code. */
static chasm_behavior_spec behaviors[7];

__attribute__((constructor)) static void collect(void)
{
    behaviors[0] = pilot_heading_behavior;
    behaviors[1] = pilot_depth_behavior;
    behaviors[2] = pilot_altitude_behavior;
    behaviors[3] = pilot_pitch_behavior;
    behaviors[4] = pilot_speed_behavior;
    behaviors[5] = pilot_rpm_behavior;
    behaviors[6] = pilot_watch_behavior;
}

CHASM_PLUGIN_EXPORT("pilot", "1.0.0", behaviors, CHASM_COUNT(behaviors), NULL, 0);
