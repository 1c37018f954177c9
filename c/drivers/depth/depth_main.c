/* auv-depth: the pressure depth sensor's driver (docs/drivers.md). Everything is
 * in its protocol (depth_protocol.c), c/drivers/pressure and the framework. */
#include "drivers/depth/depth.h"

int main(int argc, char **argv) { return drv_main(&depth_protocol, argc, argv); }
