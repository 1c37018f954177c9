// nav_unit_tests: the filter's C++ unit tests on the shared harness
// (tests/harness/unit.h; each TEST registers itself), linked with
// --wrap=malloc & co. and counted_new.cpp so that a test can prove a filter
// update allocates nothing.
//
//   nav_unit_tests [--list] [NAME]
#include "../../harness/unit.h"

int main(int argc, char **argv) { return unit_main(argc, argv, nullptr); }
