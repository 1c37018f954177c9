/* auv-servo: the fins and the thruster on a Pololu Maestro (docs/drivers.md,
 * "auv-servo"). Its input is LCM, not the device: each actuators_t of
 * <VEHICLE>.ACTUATORS becomes the channels' pulses (actuator_map.h) written
 * in the Maestro's protocol (maestro.h); the device's bytes are only the
 * replies to the driver's Get Errors polls. Device name SERVO: its status is
 * <VEHICLE>.DRIVER.SERVO, its recording <VEHICLE>.RAW.SERVO. */
#ifndef DRV_SERVO_H
#define DRV_SERVO_H

#include <stdint.h>

#include "drivers/common/drv_protocol.h"
#include "drivers/servo/actuator_map.h"
#include "drivers/servo/maestro.h"

/* Get Errors once a second; a reply not whole by the next poll is a timeout */
#define SERVO_ERRORS_POLL_US INT64_C(1000000)

typedef struct {
    int have_table;
    am_config cfg;
    am_state am;
    maestro_rx rx;
    uint16_t targets[MAESTRO_MAX_CHANNELS]; /* the pulses last sent, or to send on (re)opening */
    int64_t next_poll;                      /* the driver's clock [us]; 0: at the first tick */
    int baud_sent;                          /* the port opened with the baud indication (a Get Errors):
                                             * the next poll is a period after the tick that sees it */
    int clamp_logged, resume_logged;
} servo_state;

extern const drv_protocol servo_protocol;

#endif
