/* Publish a CHASM's state as auv.chasm_status_t for lcm-spy, the launcher and logs. */
#ifndef MGR_STATUS_H
#define MGR_STATUS_H

#include <lcm/lcm.h>

#include "chasm/chasm.h"
#include "managers/mgr_limits.h"

typedef struct {
    const char *vehicle;
    const char *manager;
    const char *plan;
    char channel[MGR_MAX_CHANNEL + 1]; /* <VEHICLE>.CHASM.<MANAGER> */
} mgr_status_ctx;

/* What the manager counted and dropped, for the status message. */
typedef struct {
    int64_t decode_errors;
    int64_t dropped_invalid_time, dropped_future, dropped_out_of_order, dropped_out_of_range;
    int64_t clock_invalid, clock_backwards, clock_jumps, clock_old_term;
    int64_t commands_refused;
    int64_t messages_in, messages_out, messages_missed, posts_refused;
} mgr_drop_counts;

void mgr_status_init(mgr_status_ctx *s, const char *vehicle, const char *manager, const char *plan);
void mgr_status_publish(const mgr_status_ctx *s, lcm_t *lcm, const chasm_machine *m, int64_t now_us,
                        const mgr_drop_counts *drops, double cycle_cost_us);

#endif
