/* auv-frontseat: a commercial vehicle's frontseat, from its backseat
 * (docs/frontseat.md). Everything is in fs_core.c and the driver framework. */
#include "frontseat/frontseat.h"

int main(int argc, char **argv) { return drv_main(&frontseat_protocol, argc, argv); }
