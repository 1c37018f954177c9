/* auv-dvl: the PD0 protocol layer (pd0.h) behind the driver framework
 * (docs/drivers.md, "auv-dvl"). */
#ifndef DRIVERS_DVL_H
#define DRIVERS_DVL_H

#include "drivers/common/drv_protocol.h"

extern const drv_protocol dvl_protocol;

#endif
