/* The checks plugin: test handlers for plans (docs/behaviors.md, "Test
 * handlers"). Each returns 1 when its criterion holds this cycle; the plan
 * adds `for T` itself. */
#ifndef CHECKS_H
#define CHECKS_H

#include "chasm/chasm_plugin.h"

#pragma GCC visibility push(hidden)

/* Each test handler's slots, schema and evaluate(), registered in
 * checks_plugin.c (one table: chasm_plugin.h, "Registration"). */

/* depth_within, altitude_within, heading_within, pitch_within (checks_within.c):
 * one schema shape, a quantity each. */
enum { WITHIN_MEASURED, WITHIN_VALUE, WITHIN_TOLERANCE, WITHIN_NPARAMS };
extern const chasm_param_spec checks_depth_within_params[WITHIN_NPARAMS],
    checks_altitude_within_params[WITHIN_NPARAMS], checks_heading_within_params[WITHIN_NPARAMS],
    checks_pitch_within_params[WITHIN_NPARAMS];
int checks_depth_within_evaluate(chasm_ctx *c);
int checks_altitude_within_evaluate(chasm_ctx *c);
int checks_heading_within_evaluate(chasm_ctx *c);
int checks_pitch_within_evaluate(chasm_ctx *c);

/* near (checks_within.c) */
enum { N_NORTH, N_EAST, N_AT_NORTH, N_AT_EAST, N_RADIUS, N_NPARAMS };
extern const chasm_param_spec checks_near_params[N_NPARAMS];
int checks_near_evaluate(chasm_ctx *c);

/* outside_area (checks_area.c) */
enum { AREA_POLYGON, AREA_NORTH, AREA_EAST, AREA_LENGTH, AREA_WIDTH, AREA_HEADING, AREA_MARGIN, AREA_AT_NORTH,
       AREA_AT_EAST, AREA_NPARAMS };
extern const chasm_param_spec checks_outside_area_params[AREA_NPARAMS];
int checks_outside_area_evaluate(chasm_ctx *c);

#pragma GCC visibility pop
#endif
