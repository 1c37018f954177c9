/* Parameter overrides as values, never plan text (cm_overrides.c). */
#ifndef CM_OVERRIDES_H
#define CM_OVERRIDES_H
#include "chasm/cm_parser.h"

/* Parse one override into the plan's parameters (depth 0: it wins). */
void cm_parse_override(cm_parse_ctx *ctx, const char *name, const char *value);
/* After every file is parsed: each override names a declared parameter and
 * has a value of its kind and unit dimension. */
void cm_check_overrides(cm_diag *d, const cm_aplan *plan);
#endif
