/* auv-modem: the WHOI Micro-Modem driver (docs/drivers.md, "auv-modem").
 * Everything is in its protocol (modem_protocol.c) and the driver framework
 * (c/drivers/common/drv_main.c). */
#include "drivers/modem/modem.h"

int main(int argc, char **argv) { return drv_main(&modem_protocol, argc, argv); }
