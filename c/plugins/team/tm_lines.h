/* The team roster and survey lines (the same strings in every vehicle's plan)
 * and the takeover rule.
 *
 *   team  = "AUV1,AUV2,AUV3,AUV4"      index in the list = team number
 *   lines = "0: 0,0 0,400; 0: 20,400 20,0; 1: 40,0 40,400"
 *           owner: from_north,from_east to_north,to_east; ...
 *
 * A vehicle's own lines are the lines it owns, in line order; search
 * vehicles are the owners of at least one line.
 *
 * Takeover rule (computed by every vehicle from what it has heard, no
 * leader). Each search vehicle works down its work list: its own lines in
 * line order, then the lines dealt to it, in the order dealt; its status
 * says how far it is (next_line: an index into that list). When a search
 * vehicle L is lost, its list from its last reported next_line on (0 if it
 * was never heard) is dealt round-robin, in list order, to the surviving
 * search vehicles sorted by team index: the first to the lowest-numbered
 * survivor, and so on, each appended to the taker's list. Every vehicle
 * keeps every teammate's list the same way, so the lines a later-lost
 * vehicle had taken over are dealt again like its own. The deal is made
 * once, when a vehicle decides L is lost, from the survivors of that moment. */
#ifndef TM_LINES_H
#define TM_LINES_H

#include <stddef.h>

#include "plugins/lib/gd_geometry.h"

#define TM_MAX_TEAM 16
#define TM_MAX_LINES 64
#define TM_NAME_LEN 24
#define TM_ALL_DONE 63   /* next_line at or beyond its list's end: every line it has is flown */

typedef struct {
    char name[TM_MAX_TEAM][TM_NAME_LEN];
    int n;
} tm_roster;

typedef struct {
    int owner;
    gd_point a, b;
} tm_line;

typedef struct {
    tm_line l[TM_MAX_LINES];
    int n;
} tm_lines;

/* Parse; 0 on success, else -1 with the reason in why, starting with the
 * character position ("at character 12: ..."). */
PU_HIDDEN int tm_roster_parse(tm_roster *r, const char *s, char *why, size_t whylen);
PU_HIDDEN int tm_roster_index(const tm_roster *r, const char *name);
/* Owners must be < n_team (n_team <= 0: only < TM_MAX_TEAM is checked). */
PU_HIDDEN int tm_lines_parse(tm_lines *l, const char *s, int n_team, char *why, size_t whylen);

/* 1 if vehicle v owns at least one line. */
PU_HIDDEN int tm_is_searcher(const tm_lines *l, int v);
/* Vehicle v's own lines (indices into l), in line order; returns the count. */
PU_HIDDEN int tm_own_lines(const tm_lines *l, int v, int *out, int max);
/* Every vehicle's work list (see the takeover rule above). */
typedef struct {
    int line[TM_MAX_TEAM][TM_MAX_LINES];
    int n[TM_MAX_TEAM];
} tm_work;

/* The lists before any deal: each vehicle's own lines. */
PU_HIDDEN void tm_work_init(tm_work *w, const tm_lines *l, int n_team);
/* The deal of lost vehicle `lost` (its list from `from` on): to[line] = the
 * survivor that takes it, -1 for the lines not dealt; each dealt line is
 * appended to its taker's list. alive[v] != 0 marks the vehicles not (yet)
 * lost; the lost vehicle itself is never a survivor. Returns the number of
 * lines dealt (0 if there is no survivor). */
PU_HIDDEN int tm_takeover_deal(tm_work *w, const tm_lines *l, int lost, int from, const int *alive, int n_team,
                               int to[TM_MAX_LINES]);

#endif
