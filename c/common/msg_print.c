#include "common/msg_print.h"

#include <inttypes.h>
#include <string.h>

static void print_prim(FILE *out, lcm_field_type_t t, const void *p)
{
    switch (t) {
    case LCM_FIELD_INT8_T: fprintf(out, "%d", *(const int8_t *)p); break;
    case LCM_FIELD_BYTE: fprintf(out, "%u", *(const uint8_t *)p); break;
    case LCM_FIELD_BOOLEAN: fprintf(out, "%s", *(const int8_t *)p ? "true" : "false"); break;
    case LCM_FIELD_INT16_T: fprintf(out, "%d", *(const int16_t *)p); break;
    case LCM_FIELD_INT32_T: fprintf(out, "%" PRId32, *(const int32_t *)p); break;
    case LCM_FIELD_INT64_T: fprintf(out, "%" PRId64, *(const int64_t *)p); break;
    case LCM_FIELD_FLOAT: fprintf(out, "%.9g", *(const float *)p); break;
    case LCM_FIELD_DOUBLE: fprintf(out, "%.17g", *(const double *)p); break;
    case LCM_FIELD_STRING: {
        /* Quote strings so values with spaces stay one token. */
        const char *s = *(char *const *)p;
        fputc('"', out);
        for (; s && *s; s++)
            fprintf(out, (*s == '"' || *s == '\\') ? "\\%c" : "%c", *s);
        fputc('"', out);
        break;
    }
    default: break;
    }
}

static void print_struct(FILE *out, const char *prefix, const auv_type_entry_t *type, const void *msg,
                         int *first);

static void print_field(FILE *out, const char *prefix, const lcm_field_t *f, int *first)
{
    /* Variable-size arrays are pointers in the struct; fixed ones are inline. */
    size_t n = 1;
    for (int d = 0; d < f->num_dim; d++)
        n *= (size_t)(f->dim_size[d] > 0 ? f->dim_size[d] : 0);
    const char *base = f->data;
    if (f->num_dim > 0 && f->dim_is_variable[0])
        base = *(char *const *)f->data;
    if (f->num_dim > 1 && f->dim_is_variable[0]) {
        fprintf(out, "%s%s%s=<%zu elements>", *first ? "" : " ", prefix, f->name, n);
        *first = 0;
        return;
    }
    if (f->type == LCM_FIELD_USER_TYPE) {
        const auv_type_entry_t *sub = auv_type_find(f->typestr);
        if (!sub)
            return;
        for (size_t i = 0; i < n; i++) {
            char p2[256];
            if (f->num_dim == 0)
                snprintf(p2, sizeof p2, "%s%s.", prefix, f->name);
            else
                snprintf(p2, sizeof p2, "%s%s[%zu].", prefix, f->name, i);
            print_struct(out, p2, sub, base + i * sub->struct_size, first);
        }
        return;
    }
    fprintf(out, "%s%s%s=", *first ? "" : " ", prefix, f->name);
    *first = 0;
    size_t sz = auv_field_elem_size(f->type);
    for (size_t i = 0; i < n && base; i++) {
        if (i)
            fputc(',', out);
        print_prim(out, f->type, base + i * sz);
    }
}

static void print_struct(FILE *out, const char *prefix, const auv_type_entry_t *type, const void *msg,
                         int *first)
{
    const lcm_type_info_t *info = type->info();
    int nf = info->num_fields();
    for (int i = 0; i < nf; i++) {
        lcm_field_t f;
        memset(&f, 0, sizeof f);
        if (info->get_field(msg, i, &f) == 0)
            print_field(out, prefix, &f, first);
    }
}

void msg_print(FILE *out, const auv_type_entry_t *type, const void *msg)
{
    int first = 1;
    print_struct(out, "", type, msg, &first);
    fputc('\n', out);
}
