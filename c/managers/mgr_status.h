/* Publish a CHASM's state as auv.chasm_status_t for lcm-spy, the launcher and logs. */
#ifndef MGR_STATUS_H
#define MGR_STATUS_H

#include <lcm/lcm.h>

#include "chasm/chasm.h"
#include "managers/mgr_limits.h"

/* What the manager counted and dropped, for the status message. */
typedef struct {
    int64_t decode_errors;
    int64_t dropped_invalid_time, dropped_future, dropped_out_of_order, dropped_out_of_range;
    int64_t clock_invalid, clock_backwards, clock_jumps, clock_old_term;
    int64_t commands_refused;
    int64_t auth_unsigned, auth_unknown_key, auth_bad_mac, auth_replay, auth_stale;
    int64_t messages_in, messages_out, messages_missed, posts_refused;
} mgr_drop_counts;

typedef struct {
    const char *vehicle;
    const char *manager;
    const char *plan;       /* the running plan's file name (plan_buf after a LOAD_PLAN) */
    char plan_buf[MGR_MAX_PLAN_NAME + 1];
    char channel[MGR_MAX_CHANNEL + 1]; /* <VEHICLE>.CHASM.<MANAGER> */
    /* --status-rate: at most one status per period of mission time, plus one
     * at once whenever something an operator acts on changed; 0: every cycle. */
    int64_t period_us;
    int published;          /* a status went out since init */
    int64_t last_us;        /* its mission time */
    double max_cost_us;     /* the costliest step since then */
    /* what the last status said that, changed, sends the next one at once */
    int run_state;
    int64_t last_transition_us;
    int path_len;
    char leaf[256];         /* leaf path, cut to fit: the transition time tells changes apart too */
    mgr_drop_counts drops;
    const char *plan_id;    /* the structure's (mgr_structure.h), "" before it is built */
} mgr_status_ctx;

/* The plan a LOAD_PLAN put in place: the statuses name it from now on (its
 * file name, as for the plan the manager started with). */
void mgr_status_set_plan(mgr_status_ctx *s, const char *plan);

/* rate_hz 0: a status every cycle (the default). */
void mgr_status_init(mgr_status_ctx *s, const char *vehicle, const char *manager, const char *plan, double rate_hz);

/* Called every cycle (and every LOADING tick): publishes the status when it
 * is due. At rate 0, always. Otherwise when the run state, the active path,
 * the last transition or any count changed since the last status, or a
 * period of mission time has passed since it (a cycle whose time reaches
 * the period's end), so what a status says is never more than a period old
 * and a change is never late. Which cycles publish depends on mission time
 * and the plan alone: lockstep reruns publish the same statuses. The
 * status's cycle_cost_us is the costliest step since the previous one.
 * 1 when it published. */
int mgr_status_update(mgr_status_ctx *s, lcm_t *lcm, const chasm_machine *m, int64_t now_us,
                      const mgr_drop_counts *drops, double cycle_cost_us);

#endif
