/* The clock a driver stamps with (--clock):
 *  - system: CLOCK_REALTIME in us, the vehicle's clock at sea (docs/channels.md:
 *    a vehicle on its system clock uses Unix time);
 *  - sim: a simulated vehicle (hardware in the loop at the wire, device
 *    emulators): the newest SIM.CLOCK accepted by the project's time rule
 *    (c/common/time_policy.h: never backwards, a jump confirmed by a second
 *    message, an old election term refused). Bytes are stamped with that
 *    value as it is, not extrapolated: no stamp runs ahead of the world's
 *    clock, and in lockstep the stamps are the steps'. Before the first clock
 *    there is no time: the driver drops what it reads (reason "no clock yet"). */
#ifndef DRV_CLOCK_H
#define DRV_CLOCK_H

#include <lcm/lcm.h>
#include <stdint.h>

#include "common/lcm_rx.h"
#include "common/time_policy.h"
#include "drivers/common/drv_options.h"

typedef struct {
    drv_clock_mode mode;
    tp_clock sim;
    tp_term term;
    int64_t refused; /* SIM.CLOCK values the time rule refused */
    rx_sub_t *sub;   /* sim mode: the SIM.CLOCK subscription, NULL otherwise */
} drv_clock;

/* sim mode subscribes to SIM.CLOCK on lcm. 0 ok, -1 failed. */
int drv_clock_init(drv_clock *c, drv_clock_mode mode, lcm_t *lcm);
/* Gives the SIM.CLOCK subscription back (before lcm is destroyed): the
 * subscription's memory is the clock's, not lcm's. */
void drv_clock_close(drv_clock *c, lcm_t *lcm);
/* Now on the chosen clock [us], or -1 when there is none yet. */
int64_t drv_clock_now(const drv_clock *c);
/* Monotonic milliseconds, for timers and backoffs whatever the clock. */
int64_t drv_monotonic_ms(void);

#endif
