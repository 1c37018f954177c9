/* Deconfliction geometry: two vehicles dead-reckoned on straight lines at
 * constant speed; their closest point of approach (CPA) within a horizon. */
#ifndef TM_KEEPCLEAR_H
#define TM_KEEPCLEAR_H

#include "plugins/lib/pu_visibility.h"

typedef struct {
    double n, e;       /* position [m] */
    double heading;    /* course over ground [rad], clockwise from north */
    double speed;      /* [m/s] */
} tm_track;

/* Moves a track forward by dt seconds. */
PU_HIDDEN tm_track tm_track_advance(tm_track a, double dt);
/* The smallest horizontal distance between a and b over [0, horizon] s;
 * *t_cpa (may be NULL) receives when. */
PU_HIDDEN double tm_cpa(tm_track a, tm_track b, double horizon, double *t_cpa);

#endif
