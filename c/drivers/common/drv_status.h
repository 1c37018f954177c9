/* A driver's 1 Hz reports: driver_status_t on <V>.DRIVER.<DEVICE> (its port,
 * bytes, frames, and a count per drop reason) and process_health_t on
 * <V>.HEALTH (decode_errors: the total of the drops). */
#ifndef DRV_STATUS_H
#define DRV_STATUS_H

#include <lcm/lcm.h>
#include <stdint.h>

#include "drivers/common/drv_ctx.h"
#include "drivers/common/drv_port.h"

typedef struct {
    double last_wall, last_cpu;
} drv_status;

void drv_status_init(drv_status *s);
void drv_status_publish(drv_status *s, lcm_t *lcm, const drv_ctx *ctx, const drv_port *port, int64_t utime);

#endif
