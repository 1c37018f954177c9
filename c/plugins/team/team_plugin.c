/* The descriptor of plugin `team` (plans: `use team`): the behaviors of a
 * cooperative MCM team over the acoustic link (docs/team.md), and the load
 * check of the roster and lines strings. */
#include <stdio.h>
#include <string.h>

#include "tm_behaviors.h"
#include "tm_lines.h"

/* One table (chasm_plugin.h, "Registration"); each behavior's schema and
 * entry points are declared in tm_behaviors.h. */
static const chasm_behavior_spec behaviors[] = {
    {.name = "team_link",
     .doc = "the team's acoustic link: TDMA frames by priority, peer table, lost teammates, team events",
     CHASM_SCHEMA(tm_link_params), .state_size = 64, .start = tm_link_start, .step = tm_link_step},
    {.name = "team_status", .doc = "queue this vehicle's status for the link (`do team_status() every 20 s`)",
     CHASM_SCHEMA(tm_status_params), .start = tm_status_start, .step = tm_status_step},
    {.name = "search_contacts", .doc = "merge sidescan looks into the contact list; report mine-like ones until acked",
     CHASM_SCHEMA(tm_search_params), .start = tm_search_start, .step = tm_search_step},
    {.name = "team_survey", .doc = "fly own lines, then lines taken over from lost teammates",
     CHASM_SCHEMA(tm_survey_params), .state_size = sizeof(tm_survey_state), .start = tm_survey_start,
     .step = tm_survey_step},
    {.name = "ri_reacquire", .doc = "reacquire-identify: route through the reported targets, identify them from looks",
     CHASM_SCHEMA(tm_ri_params), .state_size = sizeof(tm_ri_state), .start = tm_ri_start, .step = tm_ri_step},
    {.name = "follow_peer", .doc = "keep station astern or abeam of a teammate, from its status over the link",
     CHASM_SCHEMA(tm_follow_params), .state_size = sizeof(tm_follow_state), .start = tm_follow_start,
     .step = tm_follow_step},
    {.name = "front_rule",
     .doc = "sampling: the course along the front towards where the team's estimate is least certain",
     CHASM_SCHEMA(tm_front_rule_params), .state_size = sizeof(tm_front_rule_state), .start = tm_front_rule_start,
     .step = tm_front_rule_step},
    {.name = "keep_clear", .doc = "depth offset while a lower-numbered teammate is predicted close",
     CHASM_SCHEMA(tm_keepclear_params), .state_size = sizeof(tm_keepclear_state), .start = tm_keepclear_start,
     .step = tm_keepclear_step, .stop = tm_keepclear_stop},
};

CHASM_PLUGIN_EXPORT("team", "1.0.0", CHASM_BEHAVIORS(behaviors));

CHASM_PLUGIN_CHECK(check)
static int check(const char *item, const chasm_ctx *c, int *slot, char *why, size_t whylen)
{
    if (!strcmp(item, "team_link")) {
        tm_roster r;
        if (tm_roster_parse(&r, chasm_param_string(c, LINK_TEAM), why, whylen)) {
            *slot = LINK_TEAM;
            return -1;
        }
        if (tm_roster_index(&r, chasm_param_string(c, LINK_ME)) < 0) {
            *slot = LINK_ME;
            snprintf(why, whylen, "'%s' is not in the team roster", chasm_param_string(c, LINK_ME));
            return -1;
        }
        if (chasm_param_int(c, LINK_MY_SLOT) >= chasm_param_int(c, LINK_SLOTS)) {
            *slot = LINK_MY_SLOT;
            snprintf(why, whylen, "slot %lld does not exist: slots = %lld", (long long)chasm_param_int(c, LINK_MY_SLOT),
                     (long long)chasm_param_int(c, LINK_SLOTS));
            return -1;
        }
        if (chasm_param_double(c, LINK_WINDOW) > chasm_param_double(c, LINK_SLOT)) {
            *slot = LINK_WINDOW;
            snprintf(why, whylen, "longer than the slot");
            return -1;
        }
    } else if (!strcmp(item, "team_survey")) {
        tm_lines l;
        if (tm_lines_parse(&l, chasm_param_string(c, SV_LINES), 0, why, whylen)) {
            *slot = SV_LINES;
            return -1;
        }
    }
    return 0;
}
