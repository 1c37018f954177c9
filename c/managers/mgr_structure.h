/* Publish the running plan's structure as auv.chasm_structure_t on
 * <VEHICLE>.PLAN.<NAME>, so a view can draw it and a log keeps it. */
#ifndef MGR_STRUCTURE_H
#define MGR_STRUCTURE_H

#include <lcm/lcm.h>

#include "auv/auv_chasm_structure_t.h"
#include "chasm/chasm.h"
#include "managers/mgr_limits.h"

typedef struct {
    const char *vehicle, *manager;
    char channel[MGR_MAX_CHANNEL + 1];
    const chasm_machine *built_for;   /* the machine the message describes */
    auv_chasm_structure_t msg;        /* tables malloc'd, strings the machine's or owned */
    char **owned;                     /* strings formatted here */
    size_t n_owned, cap_owned;
    char plan_id[17];                 /* 16 hex digits of the digest */
    int published;                    /* sent since it was built */
    int64_t last_us;                  /* mission time of the last send */
} mgr_structure;

void mgr_structure_init(mgr_structure *s, const char *vehicle, const char *manager);
/* Describes machine m (a new or replaced plan) and computes its plan_id; the
 * next mgr_structure_update sends it. -1 out of memory (nothing sent then). */
int mgr_structure_build(mgr_structure *s, const chasm_machine *m, int64_t now_us);
/* Sends the structure when it is new, once every MGR_STRUCTURE_PERIOD_US of
 * mission time, or when the clock went back. Mission time only: lockstep
 * reruns publish the same messages. 1 when it published. */
int mgr_structure_update(mgr_structure *s, lcm_t *lcm, int64_t now_us);
void mgr_structure_free(mgr_structure *s);

#endif
