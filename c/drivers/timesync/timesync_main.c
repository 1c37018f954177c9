/* auv-timesync: the vehicle's SIM.CLOCK from the simulator's time link
 * (docs/drivers.md, "auv-timesync"); everything is in its protocol
 * (timesync_protocol.c) and the driver framework. */
#include "drivers/timesync/timesync.h"

int main(int argc, char **argv) { return drv_main(&timesync_protocol, argc, argv); }
