/* auv-servo: the fins-and-thruster driver (docs/drivers.md, "auv-servo").
 * Everything is in its protocol (servo_protocol.c) and the driver framework
 * (c/drivers/common/drv_main.c). */
#include "drivers/servo/servo.h"

int main(int argc, char **argv) { return drv_main(&servo_protocol, argc, argv); }
