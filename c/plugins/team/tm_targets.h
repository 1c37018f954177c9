/* The reacquire-identify vehicle's target queue. Contact reports arrive from
 * several search vehicles, each repeated until acknowledged; a report is
 * matched first by its name (origin, number), then by position: a report
 * within `merge` metres of a known target is the same object seen by another
 * vehicle (or a later look) and becomes an alias of that target, so the RI
 * vehicle visits each object once. Looks identify targets by position. */
#ifndef TM_TARGETS_H
#define TM_TARGETS_H

#include "plugins/lib/pu_visibility.h"

#define TM_MAX_TARGETS 256
#define TM_MAX_ALIASES 8

enum { TM_T_PENDING = 0, TM_T_IDENTIFIED = 1, TM_T_NOT_FOUND = 2 };
enum { TM_RESULT_NONE = 0, TM_RESULT_MINE = 1, TM_RESULT_NOT_MINE = 2, TM_RESULT_NOT_FOUND = 3 };

typedef struct {
    int origin, number;   /* reporting vehicle's team index, its contact number */
} tm_key;

typedef struct {
    tm_key key;                      /* the first report's name: the target's name */
    tm_key alias[TM_MAX_ALIASES];    /* other reports of the same object */
    int n_alias;
    double n, e, sigma;              /* merged estimate */
    double score;                    /* highest reported score */
    double t_first;                  /* first report heard [s] */
    int state;                       /* TM_T_* */
    int result;                      /* TM_RESULT_* once decided */
    int looks;                       /* looks that weighed in so far */
    double llr;                      /* log-likelihood ratio mine : not mine of those looks */
    double look_sum_n, look_sum_e;   /* sum of their positions (their mean is where the object is) */
    double look_n, look_e;           /* position of the deciding look */
    int engaged;                     /* came within ident range (or a pass went by) as the current target */
    double look_s;                   /* time spent on it as the current target since then [s]: a target
                                        set aside for another keeps what it had, so look_timeout is the
                                        RI vehicle's time on it, not the time since it was first near */
} tm_target;

typedef struct {
    tm_target t[TM_MAX_TARGETS];
    int n;
    long full;
} tm_target_queue;

/* One report. Returns the target index (*created = 1 if new), or -1 if the
 * queue is full (counted). */
PU_HIDDEN int tm_targets_report(tm_target_queue *q, tm_key k, double n, double e, double sigma, double score, double t,
                                double merge_m, int *created);
/* A look at an object at (n, e) with result mine (1) / not mine (2), right
 * with probability `confidence`. It counts for the nearest pending target
 * it falls near: within first_gate_m of the reports' estimate while the
 * target has no look (reports and look come from different vehicles'
 * navigation, whose errors add up), within gate_m of the mean of its looks
 * after that (one vehicle's frame, so a neighbouring object is not taken for
 * it). The target adds the look's log-likelihood ratio, and is decided once
 * the sum says one result with error probability at most max_error (Wald's
 * sequential test: |llr| >= log((1 - a) / a)): one wrong look among right
 * ones delays a decision instead of making it. A confidence that is not a
 * number or not above 0.5 says nothing and is ignored; one at or above 1 is
 * taken as 1 - 1e-9 (no look is certain). Returns the target index when this
 * look decided it, -2 if it weighed in without deciding, -1 if no pending
 * target matched or the look carries no information. */
PU_HIDDEN int tm_targets_look(tm_target_queue *q, double n, double e, int result, double confidence,
                              double first_gate_m, double gate_m, double max_error);
/* Where the object is believed to be: the mean of the looks at it once there
 * are any, else the reports' merged estimate. */
PU_HIDDEN void tm_target_where(const tm_target *t, double *n, double *e);
/* Pending targets, in index order; returns their count. */
PU_HIDDEN int tm_targets_pending(const tm_target_queue *q, int *idx, int max);

#endif
