/* The behaviors of plugin `team`: schema slots and entry points, collected
 * by team_plugin.c into the descriptor. Each schema is indexed by its slot
 * enum (see chasm_plugin.h). */
#ifndef TM_BEHAVIORS_H
#define TM_BEHAVIORS_H

#include "chasm/chasm_plugin.h"
#include "plugins/lib/gd_geometry.h"
#include "tm_lines.h"

#define TM_DECLARE(id, nparams)                                        \
    PU_HIDDEN extern const chasm_param_spec tm_##id##_params[nparams]; \
    PU_HIDDEN int tm_##id##_start(chasm_ctx *c, void *state);          \
    PU_HIDDEN chasm_status_code tm_##id##_step(chasm_ctx *c, void *state)

/* The vertical setpoint of a steering behavior (tm_steer), at its two slots:
 * a depth, or an altitude when one is given (chasm_param_given). */
#define TM_VERTICAL_PARAMS(depth, altitude)                                                                   \
    [depth] = CHASM_PARAM_DOUBLE_RANGE("depth", "m", 5, 0, 1000, "depth (plus keep_clear's offset)"),          \
    [altitude] = CHASM_PARAM_OPTIONAL("altitude", CHASM_DOUBLE, "m",                                        \
                                      "altitude instead of a depth (minus keep_clear's offset)")
#define TM_POSITION_INPUTS(north, east)                                                                       \
    [north] = CHASM_READ("in_north", CHASM_DOUBLE, "m", "nav.north_m", "vehicle north position"),              \
    [east] = CHASM_READ("in_east", CHASM_DOUBLE, "m", "nav.east_m", "vehicle east position")

/* ---- team_link (bh_team_link.c) */
enum { LINK_TEAM, LINK_ME, LINK_SLOT, LINK_SLOTS, LINK_MY_SLOT, LINK_WINDOW, LINK_FRAME_BYTES, LINK_SILENT,
       LINK_REPEAT, LINK_RX, LINK_TX, LINK_EVENTS, LINK_FRONT, LINK_NPARAMS };
TM_DECLARE(link, LINK_NPARAMS);

/* ---- team_status (bh_team_status.c) */
enum { STATUS_CODE, STATUS_NORTH, STATUS_EAST, STATUS_DEPTH, STATUS_HEADING, STATUS_SPEED, STATUS_NPARAMS };
TM_DECLARE(status, STATUS_NPARAMS);

/* ---- search_contacts (bh_search_contacts.c) */
enum { SC_RX, SC_MIN_SCORE, SC_MERGE, SC_NPARAMS };
TM_DECLARE(search, SC_NPARAMS);

/* ---- team_survey (bh_team_survey.c) */
enum { SV_LINES, SV_SPEED, SV_DEPTH, SV_ALTITUDE, SV_RADIUS, SV_LOOKAHEAD, SV_INTEGRAL, SV_IN_NORTH, SV_IN_EAST,
       SV_OUT_HEADING, SV_OUT_SPEED, SV_OUT_SPEED_MODE, SV_OUT_VERTICAL_MODE, SV_OUT_DEPTH, SV_OUT_ALTITUDE,
       SV_NPARAMS };
typedef struct {
    tm_lines lines;
    int phase;            /* 0: to the line's start, 1: along it */
    int line;             /* line index flown, -1 none */
    gd_line path;
    gd_los los;
} tm_survey_state;
TM_DECLARE(survey, SV_NPARAMS);

/* ---- front_rule (bh_front_rule.c, tm_front_rule.h) */
enum { FR_FROM, FR_TO, FR_CELL, FR_NEAR, FR_RECORD, FR_REPLAN, FR_COURSE, FR_MAX_AGE, FR_FRONT, FR_IN_NORTH, FR_IN_EAST,
       FR_OUT_COURSE, FR_OUT_TARGET, FR_OUT_ADAPTIVE, FR_NPARAMS };
typedef struct {
    double angle, offset, t_est;   /* the newest OK team estimate */
    int have_est;
    double target;                 /* along the front [m] */
    int have_target;
    double t_pick;                 /* when the target was given [s] */
    int adaptive;                  /* 1: steering by the estimate; 0: the planned course */
    int said_fallback;             /* the fallback is in the log */
    double t_record;               /* own position last recorded [s] */
    double t_status[16];           /* each teammate's status last recorded (its time) */
} tm_front_rule_state;
TM_DECLARE(front_rule, FR_NPARAMS);

/* ---- ri_reacquire (bh_ri_reacquire.c) */
enum { RI_LOOKS, RI_MERGE, RI_LOOK_GATE, RI_IDENT_RANGE, RI_LOOK_TIMEOUT, RI_IDENT_ERROR, RI_RUNOUT, RI_SPEED, RI_DEPTH, RI_ALTITUDE,
       RI_LOOKAHEAD, RI_IN_NORTH, RI_IN_EAST, RI_OUT_HEADING, RI_OUT_SPEED, RI_OUT_SPEED_MODE, RI_OUT_VERTICAL_MODE,
       RI_OUT_DEPTH, RI_OUT_ALTITUDE, RI_NPARAMS };
typedef struct {
    int current;          /* target index steered to, -1 none */
    gd_line leg;
    gd_los los;
    gd_point idle;        /* where it waits when the queue is empty */
    int idle_set;
    int close;            /* came within runout of the target: passes, not the leg */
    int passing;          /* running out straight past the target (pass_heading) */
    double pass_course;   /* course of the current pass [rad] */
    double swept;         /* the point's bearing turned through since the pass began [rad] */
} tm_ri_state;
TM_DECLARE(ri, RI_NPARAMS);

/* ---- follow_peer (bh_follow_peer.c) */
enum { FP_PEER, FP_BEHIND, FP_SIDE, FP_SPEED, FP_MIN_SPEED, FP_MAX_SPEED, FP_GAIN, FP_DEPTH, FP_ALTITUDE,
       FP_LOOKAHEAD, FP_IN_NORTH, FP_IN_EAST, FP_OUT_HEADING, FP_OUT_SPEED, FP_OUT_SPEED_MODE, FP_OUT_VERTICAL_MODE,
       FP_OUT_DEPTH, FP_OUT_ALTITUDE, FP_NPARAMS };
typedef struct {
    int peer;             /* roster index followed */
    gd_point idle;        /* where it circles until the peer's first status */
    int idle_set;
} tm_follow_state;
TM_DECLARE(follow, FP_NPARAMS);

/* ---- keep_clear (bh_keep_clear.c) */
enum { KC_RADIUS, KC_BAND, KC_HORIZON, KC_HYSTERESIS, KC_SILENT, KC_IN_NORTH, KC_IN_EAST, KC_IN_HEADING, KC_IN_SPEED,
       KC_OUT_OFFSET, KC_NPARAMS };
typedef struct {
    int active;
    int peer;
} tm_keepclear_state;
TM_DECLARE(keepclear, KC_NPARAMS);
PU_HIDDEN void tm_keepclear_stop(chasm_ctx *c, void *state);

/* The setpoint outputs of a steering behavior, in this order from slot `out`
 * (TM_STEER_OUTPUTS(out) in its schema); tm_steer writes them all each cycle. */
enum { TM_OUT_HEADING, TM_OUT_SPEED, TM_OUT_SPEED_MODE, TM_OUT_VERTICAL_MODE, TM_OUT_DEPTH, TM_OUT_ALTITUDE };
#define TM_STEER_OUTPUTS(out)                                                                              \
    [(out) + TM_OUT_HEADING] =                                                                             \
        CHASM_WRITE("out_heading", CHASM_DOUBLE, "rad", "setpoint.heading_rad", "heading setpoint"),       \
    [(out) + TM_OUT_SPEED] = CHASM_WRITE("out_speed", CHASM_DOUBLE, "m/s", "setpoint.speed_mps", "speed setpoint"), \
    [(out) + TM_OUT_SPEED_MODE] = CHASM_WRITE("out_speed_mode", CHASM_INT, "", "setpoint.speed_mode", "0 m/s"), \
    [(out) + TM_OUT_VERTICAL_MODE] =                                                                       \
        CHASM_WRITE("out_vertical_mode", CHASM_INT, "", "setpoint.vertical_mode", "0 depth, 1 altitude"),   \
    [(out) + TM_OUT_DEPTH] = CHASM_WRITE("out_depth", CHASM_DOUBLE, "m", "setpoint.depth_m", "depth setpoint"), \
    [(out) + TM_OUT_ALTITUDE] =                                                                            \
        CHASM_WRITE("out_altitude", CHASM_DOUBLE, "m", "setpoint.altitude_m", "altitude setpoint")
/* Heading, speed (m/s) and the vertical setpoint: depth + offset, or
 * altitude - offset when an altitude is given. */
PU_HIDDEN void tm_steer(chasm_ctx *c, double heading, int speed, int depth, int altitude, int out, double offset);

#endif
