/* Publish a CHASM's state as auv.chasm_status_t for lcm-spy, the launcher and logs. */
#ifndef MGR_STATUS_H
#define MGR_STATUS_H

#include <lcm/lcm.h>

#include "chasm/chasm.h"

typedef struct {
    const char *vehicle;
    const char *manager;
    const char *plan;
    char channel[64];           /* <VEHICLE>.CHASM.<MANAGER> */
} mgr_status_ctx;

void mgr_status_init(mgr_status_ctx *s, const char *vehicle, const char *manager, const char *plan);
void mgr_status_publish(const mgr_status_ctx *s, lcm_t *lcm, const chasm_machine *m, int64_t now_us,
                        int64_t decode_errors, double cycle_cost_us);

#endif
