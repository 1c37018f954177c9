#include "drivers/radio/radio.h"

int main(int argc, char **argv) { return drv_main(&radio_protocol, argc, argv); }
