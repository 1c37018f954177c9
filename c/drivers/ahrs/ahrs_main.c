/* auv-ahrs: the compass/AHRS driver (docs/drivers.md). Everything is in its
 * protocol (ahrs_protocol.c) and the driver framework (c/drivers/common). */
#include "drivers/ahrs/ahrs.h"

int main(int argc, char **argv) { return drv_main(&ahrs_protocol, argc, argv); }
