/* auv-ctd: the CTD driver (docs/drivers.md, "auv-ctd"). Everything is in its
 * protocol (ctd_protocol.c) and the driver framework (c/drivers/common). */
#include "drivers/ctd/ctd.h"

int main(int argc, char **argv) { return drv_main(&ctd_protocol, argc, argv); }
