/* bin/test_drivers: the device layer's C unit tests. Each test file of tests/drivers
 * registers its own list before main (a constructor), so adding a parser's
 * tests touches no other file. */
#include "../harness/unit.h"

int main(int argc, char **argv) { return unit_main(argc, argv, NULL); }
