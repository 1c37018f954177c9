/* The project's LCM types, found by name or fingerprint at run time.
 *
 * The table itself is generated from lcmtypes/ (build/gen/c/auv_type_table.c);
 * lcm-gen's type-info functions give each type's encode/decode and its fields,
 * so generic code (receive helpers, the blackboard mapping of the managers,
 * message printers) never needs per-type code written by hand. */
#ifndef AUV_TYPES_H
#define AUV_TYPES_H

#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm_coretypes.h>

typedef struct {
    const char *lcm_name;   /* "auv.nav_solution_t" */
    const char *c_name;     /* "auv_nav_solution_t" */
    size_t struct_size;     /* sizeof the C struct */
    const lcm_type_info_t *(*info)(void);
} auv_type_entry_t;

extern const auv_type_entry_t auv_type_table[];
extern const size_t auv_type_table_len;

/* By "auv.nav_solution_t", "nav_solution_t" or "auv_nav_solution_t"; NULL if unknown. */
const auv_type_entry_t *auv_type_find(const char *name);

/* By the 8-byte fingerprint that starts every encoded message; NULL if unknown. */
const auv_type_entry_t *auv_type_by_fingerprint(int64_t fingerprint);

/* Bytes one element of a primitive field occupies in the C struct (a string
 * is its char *); 0 for nested types. */
size_t auv_field_elem_size(lcm_field_type_t t);

/* The fingerprint at the start of an encoded message; 0 if len < 8. */
int64_t auv_fingerprint_of(const void *data, size_t len);

#endif
