/* auv-dvl: the DVL driver (docs/drivers.md). Everything is in its protocol
 * (dvl_protocol.c) and the driver framework (c/drivers/common/drv_main.c). */
#include "drivers/dvl/dvl.h"

int main(int argc, char **argv) { return drv_main(&dvl_protocol, argc, argv); }
