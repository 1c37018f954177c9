// frontest_unit_tests: the front estimator's C++ unit tests on the shared
// harness (tests/harness/unit.h; each TEST registers itself).
//
//   frontest_unit_tests [--list] [NAME]
#include "../../harness/unit.h"

int main(int argc, char **argv) { return unit_main(argc, argv, nullptr); }
