/* auv-gps: the GPS driver (docs/drivers.md). Everything is in its protocol
 * (gps_protocol.c) and the driver framework (c/drivers/common/drv_main.c). */
#include "drivers/gps/gps.h"

int main(int argc, char **argv) { return drv_main(&gps_protocol, argc, argv); }
