/* Helpers of the plan-level team tests (team_plan_kit.c). */
#ifndef TEAM_PLAN_KIT_H
#define TEAM_PLAN_KIT_H

#include "../common/plugin_test.h"
#include "team/team_codec.h"

extern const char *const TEAM_PRELUDE;   /* 17 lines */

typedef struct {
    int kind, number, result;
    double n, e;
    char origin[24];
    char text[200];
} team_ev;

chasm_machine *team_load(const char *body);
const char *team_errors(const char *body);
void team_nav(chasm_machine *m, double n, double e, double heading, double speed, double t);
/* A KIND_TEAM frame from src (its messages encoded in order) into modem_rx. */
void team_feed_frame(chasm_machine *m, const char *me, const char *src, const team_msg *msgs, int n, double t);
void team_feed_contact(chasm_machine *m, int id, double n, double e, double score, double t);
void team_feed_look(chasm_machine *m, double n, double e, int result, double t);
/* Messages of the frames posted since the last call (frames counted). */
int team_take_frames(chasm_machine *m, team_msg *out, int max, int *frames);
int team_take_events(chasm_machine *m, team_ev *out, int max);
int team_count(const team_ev *ev, int n, int kind);
const team_ev *team_find(const team_ev *ev, int n, int kind);

#endif
