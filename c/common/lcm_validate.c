#include "common/lcm_validate.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Deep enough for any sane type; a recursive type would be refused here. */
#define MAX_NESTING 16

static int walk(const auv_type_entry_t *type, const uint8_t *buf, int len, int depth);

/* Store a decoded scalar integer in the scratch struct: later variable-length
 * arrays take their size from it through get_field(). */
static void store_int(lcm_field_type_t t, const uint8_t *p, void *dst)
{
    uint64_t v = 0;
    int n = (int)auv_field_elem_size(t);
    for (int i = 0; i < n; i++)
        v = (v << 8) | p[i];
    switch (t) {
    case LCM_FIELD_INT8_T: *(int8_t *)dst = (int8_t)v; break;
    case LCM_FIELD_INT16_T: *(int16_t *)dst = (int16_t)v; break;
    case LCM_FIELD_INT32_T: *(int32_t *)dst = (int32_t)v; break;
    case LCM_FIELD_INT64_T: *(int64_t *)dst = (int64_t)v; break;
    default: break;
    }
}

static int walk_string(const uint8_t *buf, int len)
{
    if (len < 4)
        return -1;
    int32_t n = (int32_t)((uint32_t)buf[0] << 24 | (uint32_t)buf[1] << 16 | (uint32_t)buf[2] << 8 | buf[3]);
    if (n < 1 || n > len - 4 || buf[4 + n - 1] != 0)
        return -1;
    return 4 + n;
}

/* One field: `count` elements of its type. Returns bytes used or -1. */
static int walk_elements(const lcm_field_t *f, int64_t count, const uint8_t *buf, int len, int depth)
{
    int pos = 0;
    if (f->type == LCM_FIELD_STRING || f->type == LCM_FIELD_USER_TYPE) {
        const auv_type_entry_t *sub = NULL;
        if (f->type == LCM_FIELD_USER_TYPE && !(sub = auv_type_find(f->typestr)))
            return -1;
        for (int64_t i = 0; i < count; i++) {
            int used = sub ? walk(sub, buf + pos, len - pos, depth + 1) : walk_string(buf + pos, len - pos);
            if (used < 0)
                return -1;
            pos += used;
        }
        return pos;
    }
    /* Strings and nested types were walked above: only primitives here, whose
     * wire size equals their C size. */
    int64_t bytes = count * (int64_t)auv_field_elem_size(f->type);
    if (bytes > len - pos)
        return -1;
    if (f->num_dim == 0 && f->type != LCM_FIELD_FLOAT && f->type != LCM_FIELD_DOUBLE &&
        f->type != LCM_FIELD_BOOLEAN && f->type != LCM_FIELD_BYTE)
        store_int(f->type, buf, f->data);
    return (int)bytes;
}

static int walk(const auv_type_entry_t *type, const uint8_t *buf, int len, int depth)
{
    if (depth > MAX_NESTING)
        return -1;
    const lcm_type_info_t *info = type->info();
    void *scratch = calloc(1, type->struct_size);
    if (!scratch)
        return -1;
    int pos = 0, nf = info->num_fields();
    for (int i = 0; i < nf && pos >= 0; i++) {
        lcm_field_t f;
        memset(&f, 0, sizeof f);
        if (info->get_field(scratch, i, &f) != 0) {
            pos = -1;
            break;
        }
        int64_t count = 1;
        for (int d = 0; d < f.num_dim; d++) {
            if (f.dim_size[d] < 0 || count > INT32_MAX) {
                count = -1;
                break;
            }
            count *= f.dim_size[d];
        }
        int used = count < 0 ? -1 : walk_elements(&f, count, buf + pos, len - pos, depth);
        pos = used < 0 ? -1 : pos + used;
    }
    free(scratch);
    return pos;
}

int lcm_validate_body(const auv_type_entry_t *type, const void *buf, int len)
{
    if (!type || !buf || len < 0)
        return -1;
    return walk(type, buf, len, 0);
}
