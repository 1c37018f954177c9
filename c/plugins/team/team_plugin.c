/* The descriptor of plugin `team` (plans: `use team`): the behaviors of a
 * cooperative MCM team over the acoustic link (docs/team.md), and the load
 * check of the roster and lines strings. */
#include <stdio.h>
#include <string.h>

#include "tm_behaviors.h"
#include "tm_lines.h"

static const chasm_behavior_spec behaviors[] = {
    {"team_link", "the team's acoustic link: TDMA frames by priority, peer table, lost teammates, team events",
     tm_link_params, LINK_NPARAMS, 64, tm_link_start, tm_link_step, NULL},
    {"team_status", "queue this vehicle's status for the link (`do team_status() every 20 s`)", tm_status_params,
     STATUS_NPARAMS, 0, tm_status_start, tm_status_step, NULL},
    {"search_contacts", "merge sidescan looks into the contact list; report mine-like ones until acked",
     tm_search_params, SC_NPARAMS, 0, tm_search_start, tm_search_step, NULL},
    {"team_survey", "fly own lines, then lines taken over from lost teammates", tm_survey_params, SV_NPARAMS,
     sizeof(tm_survey_state), tm_survey_start, tm_survey_step, NULL},
    {"ri_reacquire", "reacquire-identify: route through the reported targets, identify them from looks",
     tm_ri_params, RI_NPARAMS, sizeof(tm_ri_state), tm_ri_start, tm_ri_step, NULL},
    {"follow_peer", "keep station astern or abeam of a teammate, from its status over the link", tm_follow_params,
     FP_NPARAMS, sizeof(tm_follow_state), tm_follow_start, tm_follow_step, NULL},
    {"keep_clear", "depth offset while a lower-numbered teammate is predicted close", tm_keepclear_params,
     KC_NPARAMS, sizeof(tm_keepclear_state), tm_keepclear_start, tm_keepclear_step, tm_keepclear_stop},
};

CHASM_PLUGIN_EXPORT("team", "1.0.0", behaviors, CHASM_COUNT(behaviors), NULL, 0);

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
