/* auv-payload: contacts and looks from the simulator's payload link
 * (docs/drivers.md, "auv-payload"); everything is in its protocol
 * (payload_protocol.c) and the driver framework. */
#include "drivers/payload/payload.h"

int main(int argc, char **argv) { return drv_main(&payload_protocol, argc, argv); }
