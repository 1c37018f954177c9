/* Resolve "depth_m", "position_cov_m2[0][2]" or "eta[5]" in an LCM type to a
 * typed reference (offset into the C struct + primitive type), once, at init.
 * Managers use this to copy message fields into the CHASM blackboard and
 * blackboard variables into outgoing messages every cycle without any
 * per-field code and without string work in the cycle. */
#ifndef AUV_FIELD_PATH_H
#define AUV_FIELD_PATH_H

#include <stdbool.h>
#include <stddef.h>

#include "common/auv_types.h"

typedef struct {
    lcm_field_type_t type;  /* a primitive: never USER_TYPE */
    size_t offset;          /* bytes from the start of the struct */
} field_ref_t;

/* 0 on success; -1 with a message in err (with a did-you-mean hint when a
 * field name is close to a real one). Variable-length arrays cannot be bound:
 * their storage is not inside the struct. */
int field_path_resolve(const auv_type_entry_t *type, const char *path, field_ref_t *out,
                       char *err, size_t errlen);

bool field_ref_is_numeric(const field_ref_t *r);
/* Numeric fields (ints, floats, booleans as 0/1) as double. */
double field_ref_get_double(const field_ref_t *r, const void *msg);
void field_ref_set_double(const field_ref_t *r, void *msg, double v);
/* String fields: the struct's char* (may be NULL). */
const char *field_ref_get_string(const field_ref_t *r, const void *msg);

/* Levenshtein distance, for did-you-mean hints. */
size_t edit_distance(const char *a, const char *b);

#endif
