#include "common/auv_types.h"

#include <string.h>

const auv_type_entry_t *auv_type_find(const char *name)
{
    if (!name)
        return NULL;
    for (size_t i = 0; i < auv_type_table_len; i++) {
        const auv_type_entry_t *e = &auv_type_table[i];
        const char *dot = strrchr(e->lcm_name, '.');
        const char *bare = dot ? dot + 1 : e->lcm_name;
        if (!strcmp(name, e->lcm_name) || !strcmp(name, e->c_name) || !strcmp(name, bare))
            return e;
    }
    return NULL;
}

const auv_type_entry_t *auv_type_by_fingerprint(int64_t fingerprint)
{
    for (size_t i = 0; i < auv_type_table_len; i++)
        if (auv_type_table[i].info()->get_hash() == fingerprint)
            return &auv_type_table[i];
    return NULL;
}

int64_t auv_fingerprint_of(const void *data, size_t len)
{
    if (len < 8)
        return 0;
    /* LCM writes the fingerprint big-endian. */
    const uint8_t *b = data;
    uint64_t v = 0;
    for (int i = 0; i < 8; i++)
        v = (v << 8) | b[i];
    return (int64_t)v;
}

size_t auv_field_elem_size(lcm_field_type_t t)
{
    switch (t) {
    case LCM_FIELD_INT8_T: case LCM_FIELD_BYTE: case LCM_FIELD_BOOLEAN: return 1;
    case LCM_FIELD_INT16_T: return 2;
    case LCM_FIELD_INT32_T: case LCM_FIELD_FLOAT: return 4;
    case LCM_FIELD_INT64_T: case LCM_FIELD_DOUBLE: return 8;
    case LCM_FIELD_STRING: return sizeof(char *);
    default: return 0;
    }
}
