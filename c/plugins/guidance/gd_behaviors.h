/* The behaviors of plugin `guidance`: schema slots, per-instance state and
 * entry points, collected by guidance_plugin.c into the plugin descriptor.
 * Each schema is indexed by its slot enum (see chasm_plugin.h). Only the
 * descriptor is exported: two plugins (or versions) never share these symbols. */
#ifndef GD_BEHAVIORS_H
#define GD_BEHAVIORS_H

#include "chasm/chasm_plugin.h"
#include "plugins/lib/gd_geometry.h"
#include "gd_survey.h"

/* Declares one behavior's schema and entry points. */
#define GD_DECLARE(id, nparams)                                            \
    PU_HIDDEN extern const chasm_param_spec gd_##id##_params[nparams];     \
    PU_HIDDEN int gd_##id##_start(chasm_ctx *c, void *state);              \
    PU_HIDDEN chasm_status_code gd_##id##_step(chasm_ctx *c, void *state)

/* ---- goto, track (bh_los.c): ILOS along a straight line */
enum { GOTO_NORTH, GOTO_EAST, GOTO_SPEED, GOTO_RADIUS, GOTO_LOOKAHEAD, GOTO_INTEGRAL, GOTO_IN_NORTH, GOTO_IN_EAST,
       GOTO_OUT_HEADING, GOTO_OUT_SPEED, GOTO_OUT_SPEED_MODE, GOTO_NPARAMS };
enum { TRACK_FROM_NORTH, TRACK_FROM_EAST, TRACK_TO_NORTH, TRACK_TO_EAST, TRACK_SPEED, TRACK_LOOKAHEAD,
       TRACK_INTEGRAL, TRACK_IN_NORTH, TRACK_IN_EAST, TRACK_OUT_HEADING, TRACK_OUT_SPEED, TRACK_OUT_SPEED_MODE,
       TRACK_NPARAMS };
typedef struct {
    gd_line line;
    gd_los los;
} gd_los_state;
GD_DECLARE(goto, GOTO_NPARAMS);
GD_DECLARE(track, TRACK_NPARAMS);

/* ---- lawnmower (bh_lawnmower.c) */
enum { MOW_NORTH, MOW_EAST, MOW_LENGTH, MOW_WIDTH, MOW_POLYGON, MOW_HEADING, MOW_SPACING, MOW_TURN_RADIUS, MOW_LEAD,
       MOW_SPEED, MOW_LOOKAHEAD, MOW_INTEGRAL, MOW_IN_NORTH, MOW_IN_EAST, MOW_OUT_HEADING, MOW_OUT_SPEED,
       MOW_OUT_SPEED_MODE, MOW_PROGRESS, MOW_NPARAMS };
typedef struct {
    gd_track lines[GD_MAX_LINES];
    int n_lines;
    int line;          /* the line being flown or turned to (the progress variable) */
    int turning;       /* 1: on the turn from line - 1 to line */
    double lead;       /* run-in / run-out beyond the area [m] */
    gd_line path;      /* the current line extended by its run-in and run-out */
    gd_los los;
    gd_point centre;   /* of the turn */
    double turn_r;
    int turn_cw;
    double turn_since_s; /* time in state when the turn began */
} gd_mow_state;
GD_DECLARE(lawnmower, MOW_NPARAMS);
/* The flown path of line k of s: the survey line extended so that it starts
 * and ends `lead` beyond both its own ends and its neighbours' (exposed for the
 * unit tests). */
PU_HIDDEN gd_line gd_mow_path(const gd_mow_state *s, int k);

/* ---- hold_depth, hold_altitude, hold_heading, set_speed (bh_hold.c) */
enum { HDEPTH_DEPTH, HDEPTH_OUT_VERTICAL_MODE, HDEPTH_OUT_DEPTH, HDEPTH_NPARAMS };
enum { HALT_ALTITUDE, HALT_OUT_VERTICAL_MODE, HALT_OUT_ALTITUDE, HALT_NPARAMS };
enum { HHEAD_HEADING, HHEAD_OUT_HEADING, HHEAD_NPARAMS };
enum { SPEED_SPEED, SPEED_RPM, SPEED_OUT_SPEED_MODE, SPEED_OUT_SPEED, SPEED_OUT_RPM, SPEED_NPARAMS };
GD_DECLARE(hold_depth, HDEPTH_NPARAMS);
GD_DECLARE(hold_altitude, HALT_NPARAMS);
GD_DECLARE(hold_heading, HHEAD_NPARAMS);
GD_DECLARE(set_speed, SPEED_NPARAMS);

/* ---- loiter (bh_loiter.c): circle following */
enum { LOITER_NORTH, LOITER_EAST, LOITER_RADIUS, LOITER_SPEED, LOITER_CLOCKWISE, LOITER_LOOKAHEAD, LOITER_IN_NORTH,
       LOITER_IN_EAST, LOITER_OUT_HEADING, LOITER_OUT_SPEED, LOITER_OUT_SPEED_MODE, LOITER_NPARAMS };
GD_DECLARE(loiter, LOITER_NPARAMS);

/* ---- yoyo (bh_yoyo.c): a ramped depth or altitude setpoint between two limits */
enum { YOYO_MIN_DEPTH, YOYO_MAX_DEPTH, YOYO_MIN_ALTITUDE, YOYO_MAX_ALTITUDE, YOYO_PITCH, YOYO_RATE, YOYO_FLOOR,
       YOYO_IN_DEPTH, YOYO_IN_ALTITUDE, YOYO_IN_SPEED, YOYO_OUT_VERTICAL_MODE, YOYO_OUT_DEPTH, YOYO_OUT_ALTITUDE,
       YOYO_OUT_PROFILES, YOYO_NPARAMS };
typedef struct {
    int altitude_mode;  /* 1: between altitudes */
    double lo, hi;      /* the band, in depth or altitude */
    double target;      /* the ramped setpoint */
    int down;           /* 1: depth increasing (altitude decreasing) */
    int64_t profiles;   /* dives and climbs completed (reversals) */
} gd_yoyo_state;
GD_DECLARE(yoyo, YOYO_NPARAMS);

/* ---- front_zigzag (bh_zigzag.c): legs at +-angle to a course, turning when
 * the CTD's temperature says the front has been crossed */
enum { ZZ_COURSE, ZZ_ANGLE, ZZ_DELTA, ZZ_FRACTION, ZZ_STEADY, ZZ_WINDOW, ZZ_SETTLE, ZZ_MAX_LEG, ZZ_CROSSINGS,
       ZZ_FIRST_RIGHT, ZZ_SPEED, ZZ_LOOKAHEAD, ZZ_INTEGRAL, ZZ_IN_NORTH, ZZ_IN_EAST, ZZ_IN_TEMPERATURE, ZZ_IN_VALID,
       ZZ_OUT_HEADING, ZZ_OUT_SPEED, ZZ_OUT_SPEED_MODE, ZZ_OUT_CROSSINGS, ZZ_OUT_CROSSING_NORTH,
       ZZ_OUT_CROSSING_EAST, ZZ_OUT_CROSSING_TIME, ZZ_OUT_LEG, ZZ_IN_COURSE, ZZ_NPARAMS };
#define GD_ZZ_CAP 64 /* samples of the along-track window (it holds about 21) */
typedef struct {
    double s;          /* along the leg [m] */
    double t_c;        /* temperature, the mean of the bin [degC] */
    double n, e, time; /* where and when (mean of the bin) [m, m, s] */
} gd_zz_sample;
/* The along-track fit of the temperature over the window (gd_zz_fit). */
typedef struct {
    int ok;            /* enough samples over enough of the window */
    double level;      /* at the newest sample [degC] */
    double gradient;   /* d temperature / d along-track [degC/m] */
    gd_zz_sample centre; /* mean position and time of the window's samples */
} gd_zz_fit_t;
typedef struct {
    gd_line line;
    gd_los los;
    int side;          /* +1: this leg is course + angle; -1: course - angle */
    int leg;           /* legs begun, from 1 */
    int64_t crossings;
    gd_zz_sample buf[GD_ZZ_CAP]; /* binned samples, oldest first from head */
    int head, count;
    long bin;          /* index of the bin being filled (along / bin width) */
    double acc_s, acc_t, acc_n, acc_e, acc_time;
    int acc_k;         /* readings in it */
    int have_ref;      /* the leg's reference temperature is taken */
    double t_ref, g_peak;
    gd_zz_sample at_peak;
    double course;     /* the course of the leg flown (in_course's, or the param) */
} gd_zz_state;
GD_DECLARE(front_zigzag, ZZ_NPARAMS);
/* Least-squares line of temperature against along-track over the last
 * `window` metres of s's samples (exposed for the unit tests). */
PU_HIDDEN gd_zz_fit_t gd_zz_fit(const gd_zz_state *s, double window);

/* ---- surface, surface_fix, timer (bh_surface.c) */
enum { SURF_PITCH, SURF_RPM, SURF_DEPTH, SURF_SPEED, SURF_IN_DEPTH, SURF_OUT_VERTICAL_MODE, SURF_OUT_PITCH,
       SURF_OUT_SPEED_MODE, SURF_OUT_RPM, SURF_OUT_DEPTH, SURF_OUT_SPEED, SURF_NPARAMS };
enum { FIX_TIMEOUT, FIX_PITCH, FIX_RPM, FIX_IN_GPS, FIX_OUT_VERTICAL_MODE, FIX_OUT_PITCH, FIX_OUT_SPEED_MODE,
       FIX_OUT_RPM, FIX_NPARAMS };
enum { TIMER_DURATION, TIMER_NPARAMS };
GD_DECLARE(surface, SURF_NPARAMS);
GD_DECLARE(surface_fix, FIX_NPARAMS);
GD_DECLARE(timer, TIMER_NPARAMS);

#endif
