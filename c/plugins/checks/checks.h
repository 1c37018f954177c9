/* The checks plugin: test handlers for plans (docs/behaviors.md, "Test
 * handlers"). Each returns 1 when its criterion holds this cycle; the plan
 * adds `for T` itself. */
#ifndef CHECKS_H
#define CHECKS_H

#include "chasm/chasm_plugin.h"

#pragma GCC visibility push(hidden)

extern const chasm_test_spec checks_depth_within, checks_altitude_within, checks_heading_within,
    checks_pitch_within, checks_near, checks_outside_area;

#pragma GCC visibility pop
#endif
