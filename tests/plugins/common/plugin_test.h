/* The C unit tests of plugins (the files in tests/plugins/NAME, linked into
 * build/bin/test_plugin_NAME with the plugin's objects, the shared plugin
 * lib, libchasm and the shared harness tests/harness: unit.h for the checks
 * and the runner, plan_test.h for plans loaded with the real libchasm).
 *
 *   test_plugin_NAME --plugins DIR [--list] [TEST]     run one test, or all
 *
 * A plugin's tests define `const unit_test plugin_tests[]`, ending in
 * {NULL, NULL}; plugin_main.c runs them. */
#ifndef PLUGIN_TEST_H
#define PLUGIN_TEST_H

#include "../../harness/plan_test.h"

extern const unit_test plugin_tests[];

#endif
