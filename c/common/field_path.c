#include "common/field_path.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

size_t edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 64 || lb > 64)
        return (size_t)-1;
    size_t row[65];
    for (size_t j = 0; j <= lb; j++)
        row[j] = j;
    for (size_t i = 1; i <= la; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; j++) {
            size_t up = row[j];
            size_t best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best)
                best = up + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

int field_path_resolve(const auv_type_entry_t *type, const char *path, field_ref_t *out,
                       char *err, size_t errlen)
{
    char name[128];
    size_t n = strcspn(path, "[");
    if (n == 0 || n >= sizeof name) {
        snprintf(err, errlen, "'%s' is not a field path", path);
        return -1;
    }
    memcpy(name, path, n);
    name[n] = '\0';

    const lcm_type_info_t *info = type->info();
    void *blank = calloc(1, type->struct_size);
    if (!blank) {
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    lcm_field_t f;
    const char *best_name = NULL;
    size_t best = (size_t)-1;
    int found = 0;
    for (int i = 0; i < info->num_fields() && !found; i++) {
        memset(&f, 0, sizeof f);
        if (info->get_field(blank, i, &f) != 0)
            continue;
        if (!strcmp(f.name, name))
            found = 1;
        else if (edit_distance(f.name, name) < best) {
            best = edit_distance(f.name, name);
            best_name = f.name;
        }
    }
    int rc = -1;
    const char *short_name = strrchr(type->lcm_name, '.') ? strrchr(type->lcm_name, '.') + 1 : type->lcm_name;
    if (!found) {
        if (best_name && best <= 3)
            snprintf(err, errlen, "%s has no field '%s' (did you mean '%s'?)", short_name, name, best_name);
        else
            snprintf(err, errlen, "%s has no field '%s'", short_name, name);
    } else if (f.type == LCM_FIELD_USER_TYPE) {
        snprintf(err, errlen, "%s.%s is a nested %s: bind one of its fields instead", short_name, name, f.typestr);
    } else {
        size_t offset = (size_t)((const char *)f.data - (const char *)blank);
        const char *p = path + n;
        int d = 0;
        rc = 0;
        while (*p == '[' && rc == 0) {
            char *end;
            long idx = strtol(p + 1, &end, 10);
            if (end == p + 1 || *end != ']') {
                snprintf(err, errlen, "'%s': bad index", path);
                rc = -1;
            } else if (d >= f.num_dim) {
                snprintf(err, errlen, "'%s': %s has %d dimension(s)", path, name, f.num_dim);
                rc = -1;
            } else if (f.dim_is_variable[d]) {
                snprintf(err, errlen, "'%s': %s has a variable length and cannot be bound", path, name);
                rc = -1;
            } else if (idx < 0 || idx >= f.dim_size[d]) {
                snprintf(err, errlen, "'%s': index %ld out of range [0, %d)", path, idx, f.dim_size[d]);
                rc = -1;
            } else {
                size_t stride = auv_field_elem_size(f.type);
                for (int k = d + 1; k < f.num_dim; k++)
                    stride *= (size_t)f.dim_size[k];
                offset += (size_t)idx * stride;
                d++;
                p = end + 1;
            }
        }
        if (rc == 0 && *p) {
            snprintf(err, errlen, "'%s': unexpected '%s'", path, p);
            rc = -1;
        } else if (rc == 0 && d != f.num_dim) {
            snprintf(err, errlen, "'%s': %s is an array of %d dimension(s): give every index", path, name,
                     f.num_dim);
            rc = -1;
        }
        if (rc == 0) {
            out->type = f.type;
            out->offset = offset;
        }
    }
    free(blank);
    return rc;
}

bool field_ref_is_numeric(const field_ref_t *r)
{
    return r->type != LCM_FIELD_STRING && r->type != LCM_FIELD_USER_TYPE;
}

double field_ref_get_double(const field_ref_t *r, const void *msg)
{
    const char *p = (const char *)msg + r->offset;
    switch (r->type) {
    case LCM_FIELD_INT8_T: return *(const int8_t *)p;
    case LCM_FIELD_BYTE: return *(const uint8_t *)p;
    case LCM_FIELD_BOOLEAN: return *(const int8_t *)p ? 1.0 : 0.0;
    case LCM_FIELD_INT16_T: return *(const int16_t *)p;
    case LCM_FIELD_INT32_T: return *(const int32_t *)p;
    case LCM_FIELD_INT64_T: return (double)*(const int64_t *)p;
    case LCM_FIELD_FLOAT: return *(const float *)p;
    case LCM_FIELD_DOUBLE: return *(const double *)p;
    default: return NAN;
    }
}

void field_ref_set_double(const field_ref_t *r, void *msg, double v)
{
    char *p = (char *)msg + r->offset;
    /* Integers saturate rather than wrap: a setpoint must never flip sign. */
#define CLAMP(lo, hi) (isnan(v) ? 0 : v < (double)(lo) ? (lo) : v > (double)(hi) ? (hi) : llround(v))
    switch (r->type) {
    case LCM_FIELD_INT8_T: *(int8_t *)p = (int8_t)CLAMP(INT8_MIN, INT8_MAX); break;
    case LCM_FIELD_BYTE: *(uint8_t *)p = (uint8_t)CLAMP(0, UINT8_MAX); break;
    case LCM_FIELD_BOOLEAN: *(int8_t *)p = v != 0.0 && !isnan(v); break;
    case LCM_FIELD_INT16_T: *(int16_t *)p = (int16_t)CLAMP(INT16_MIN, INT16_MAX); break;
    case LCM_FIELD_INT32_T: *(int32_t *)p = (int32_t)CLAMP(INT32_MIN, INT32_MAX); break;
    case LCM_FIELD_INT64_T:
        *(int64_t *)p = isnan(v) ? 0 : v <= -9.2e18 ? INT64_MIN : v >= 9.2e18 ? INT64_MAX : llround(v);
        break;
    case LCM_FIELD_FLOAT: *(float *)p = (float)v; break;
    case LCM_FIELD_DOUBLE: *(double *)p = v; break;
    default: break;
    }
#undef CLAMP
}

const char *field_ref_get_string(const field_ref_t *r, const void *msg)
{
    if (r->type != LCM_FIELD_STRING)
        return NULL;
    return *(char *const *)((const char *)msg + r->offset);
}
