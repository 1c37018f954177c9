/* Print any project message as one line of `field=value` pairs, by walking
 * lcm-gen's type info (no per-type code). Nested structs print as
 * `outer.inner=value`, arrays as comma-separated values or `name[i].field=`.
 * Used by auv-lcm-probe, tests, and for humans reading traffic in a terminal. */
#ifndef AUV_MSG_PRINT_H
#define AUV_MSG_PRINT_H

#include <stdio.h>

#include "common/auv_types.h"

void msg_print(FILE *out, const auv_type_entry_t *type, const void *msg);

#endif
