/* The manager's mission clock: SIM.CLOCK (--clock sim, with lockstep
 * participation) or the host's clock (--clock system), every reading under
 * the time rule (docs/channels.md, "Time and timestamps"). */
#ifndef MGR_CLOCK_H
#define MGR_CLOCK_H

#include "managers/manager.h"

/* Subscribes to SIM.CLOCK; 0 or -1. */
int mgr_clock_subscribe(manager_t *mg);
/* Offers the system clock's time (--clock system). */
void mgr_clock_read_system(manager_t *mg);

#endif
