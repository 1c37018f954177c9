#include "managers/mgr_bindings.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int expand_vehicle(const char *in, const char *vehicle, char *out, size_t outlen)
{
    size_t o = 0;
    for (const char *p = in; *p; p++) {
        if (!strncmp(p, "${VEHICLE}", 10)) {
            size_t n = strlen(vehicle);
            if (o + n >= outlen)
                return -1;
            memcpy(out + o, vehicle, n);
            o += n;
            p += 9;
        } else {
            if (o + 1 >= outlen)
                return -1;
            out[o++] = *p;
        }
    }
    out[o] = '\0';
    return 0;
}

/* Copy a decoded message's bound fields into the blackboard. */
static void on_input(const char *channel, const void *msg, int64_t recv_utime, void *user)
{
    (void)channel;
    (void)recv_utime;
    mgr_message_binding *mb = user;
    mgr_bindings *b = mb->owner;
    /* The message's own time of validity: plans compute message age from it. */
    int64_t utime = mb->has_utime ? (int64_t)field_ref_get_double(&mb->utime, msg) : 0;
    for (int i = 0; i < mb->n_vars; i++) {
        const mgr_var_binding *v = &mb->vars[i];
        switch (v->var_type) {
        case CHASM_DOUBLE:
            chasm_var_set_double(b->machine, v->var, field_ref_get_double(&v->field, msg), utime);
            break;
        case CHASM_INT:
            chasm_var_set_int(b->machine, v->var, (int64_t)field_ref_get_double(&v->field, msg), utime);
            break;
        case CHASM_BOOL:
            chasm_var_set_bool(b->machine, v->var, field_ref_get_double(&v->field, msg) != 0.0, utime);
            break;
        case CHASM_STRING: {
            const char *s = field_ref_get_string(&v->field, msg);
            chasm_var_set_string(b->machine, v->var, s ? s : "", utime);
            break;
        }
        }
    }
    b->inputs_applied++;
}

static int parse_file(mgr_bindings *b, const char *path, const char *vehicle)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "%s: cannot open binding file\n", path);
        return 1;
    }
    char line[512];
    int lineno = 0, errors = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char dir[32], prefix[64], channel[128], type[96], flag[16], extra[8];
        int n = sscanf(line, "%31s %63s %127s %95s %15s %7s", dir, prefix, channel, type, flag, extra);
        if (n <= 0)
            continue;
        int col = (int)(strspn(line, " \t") + 1);
        if (n < 4 || n > 5 || (strcmp(dir, "input") && strcmp(dir, "output"))) {
            fprintf(stderr, "%s:%d:%d: expected `input|output PREFIX CHANNEL TYPE [optional]`\n", path, lineno, col);
            errors++;
            continue;
        }
        /* `optional`: an input that may be absent when the plan starts (GPS
         * only exists at the surface); the plan sees its variables as never
         * written until the first message. */
        if (n == 5 && (strcmp(flag, "optional") || strcmp(dir, "input"))) {
            fprintf(stderr, "%s:%d:%d: %s\n", path, lineno, (int)(strstr(line, flag) - line) + 1,
                    strcmp(flag, "optional") ? "the only flag after the type is `optional`"
                                             : "only an input can be optional");
            errors++;
            continue;
        }
        const auv_type_entry_t *t = auv_type_find(type);
        if (!t) {
            fprintf(stderr, "%s:%d:%d: unknown message type '%s'\n", path, lineno,
                    (int)(strstr(line, type) - line) + 1, type);
            errors++;
            continue;
        }
        mgr_message_binding *grown = realloc(b->msgs, (size_t)(b->n_msgs + 1) * sizeof *grown);
        if (!grown)
            break;
        b->msgs = grown;
        mgr_message_binding *mb = &b->msgs[b->n_msgs++];
        memset(mb, 0, sizeof *mb);
        mb->is_output = !strcmp(dir, "output");
        mb->optional = n == 5;
        snprintf(mb->prefix, sizeof mb->prefix, "%s", prefix);
        if (expand_vehicle(channel, vehicle, mb->channel, sizeof mb->channel) != 0 || strlen(mb->channel) > 62) {
            fprintf(stderr, "%s:%d:%d: channel name too long (LCM allows 63 characters)\n", path, lineno, col);
            errors++;
        }
        mb->type = t;
        mb->line = lineno;
        for (int k = 0; k < b->n_msgs - 1; k++)
            if (!strcmp(b->msgs[k].prefix, prefix)) {
                fprintf(stderr, "%s:%d:%d: prefix '%s' is already bound on line %d\n", path, lineno, col,
                        prefix, b->msgs[k].line);
                errors++;
            }
    }
    fclose(f);
    return errors;
}

static int bind_var(mgr_bindings *b, const char *path, int var)
{
    const char *name = chasm_var_name(b->machine, var);
    chasm_var_kind kind = chasm_var_kind_of(b->machine, var);
    const char *dot = strchr(name, '.');
    size_t plen = dot ? (size_t)(dot - name) : 0;
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (!dot || strlen(mb->prefix) != plen || strncmp(mb->prefix, name, plen))
            continue;
        if (mb->is_output != (kind == CHASM_VAR_OUTPUT)) {
            fprintf(stderr, "%s:%d:1: plan %s '%s' is bound as an %s\n", path, mb->line,
                    kind == CHASM_VAR_OUTPUT ? "output" : "input", name, mb->is_output ? "output" : "input");
            return 1;
        }
        mgr_var_binding vb = {var, chasm_var_type(b->machine, var), {0, 0}};
        char err[256];
        if (field_path_resolve(mb->type, dot + 1, &vb.field, err, sizeof err) != 0) {
            fprintf(stderr, "%s:%d:1: plan variable '%s': %s\n", path, mb->line, name, err);
            return 1;
        }
        if ((vb.var_type == CHASM_STRING) != !field_ref_is_numeric(&vb.field)) {
            fprintf(stderr, "%s:%d:1: plan variable '%s' is %s but the field is %s\n", path, mb->line, name,
                    vb.var_type == CHASM_STRING ? "a string" : "a number",
                    vb.var_type == CHASM_STRING ? "a number" : "a string");
            return 1;
        }
        mgr_var_binding *grown = realloc(mb->vars, (size_t)(mb->n_vars + 1) * sizeof *grown);
        if (!grown)
            return 1;
        mb->vars = grown;
        mb->vars[mb->n_vars++] = vb;
        return 0;
    }
    fprintf(stderr, "%s:1:1: plan %s '%s' has no binding (no `%s %.*s ...` line)\n", path,
            kind == CHASM_VAR_OUTPUT ? "output" : "input", name,
            kind == CHASM_VAR_OUTPUT ? "output" : "input", (int)plen, name);
    return 1;
}

/* Output structs start zeroed with every string "" (lcm-gen's encoder calls
 * strlen on string pointers), and get utime and vehicle set every cycle. */
static void prepare_output(mgr_bindings *b, mgr_message_binding *mb)
{
    const lcm_type_info_t *info = mb->type->info();
    mb->scratch = calloc(1, mb->type->struct_size);
    for (int i = 0; i < info->num_fields(); i++) {
        lcm_field_t f;
        memset(&f, 0, sizeof f);
        if (info->get_field(mb->scratch, i, &f) == 0 && f.type == LCM_FIELD_STRING && f.num_dim == 0)
            *(const char **)f.data = "";
    }
    char err[128];
    mb->has_utime = field_path_resolve(mb->type, "utime", &mb->utime, err, sizeof err) == 0;
    mb->has_vehicle = field_path_resolve(mb->type, "vehicle", &mb->vehicle, err, sizeof err) == 0;
    if (mb->has_vehicle)
        *(const char **)((char *)mb->scratch + mb->vehicle.offset) = b->vehicle;
}

int mgr_bindings_load(mgr_bindings *b, const char *path, const char *vehicle, chasm_machine *m)
{
    memset(b, 0, sizeof *b);
    b->machine = m;
    b->vehicle = vehicle;
    int errors = parse_file(b, path, vehicle);
    for (size_t v = 0; v < chasm_var_count(m); v++)
        if (chasm_var_kind_of(m, (int)v) != CHASM_VAR_LOCAL)
            errors += bind_var(b, path, (int)v);
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        char err[128];
        if (!mb->is_output)
            mb->has_utime = field_path_resolve(mb->type, "utime", &mb->utime, err, sizeof err) == 0;
        else
            prepare_output(b, mb);
    }
    return errors;
}

int mgr_bindings_subscribe(mgr_bindings *b, lcm_t *lcm)
{
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (mb->is_output || mb->n_vars == 0)
            continue;
        mb->owner = b;
        mb->sub = rx_subscribe(lcm, mb->channel, mb->type, on_input, mb);
        if (!mb->sub)
            return -1;
    }
    return 0;
}

void mgr_bindings_publish(mgr_bindings *b, lcm_t *lcm, int64_t now_us)
{
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (!mb->is_output || mb->n_vars == 0)
            continue;
        for (int k = 0; k < mb->n_vars; k++) {
            const mgr_var_binding *v = &mb->vars[k];
            if (v->var_type == CHASM_STRING)
                *(const char **)((char *)mb->scratch + v->field.offset) = chasm_var_get_string(b->machine, v->var);
            else
                field_ref_set_double(&v->field, mb->scratch, chasm_var_get_double(b->machine, v->var));
        }
        if (mb->has_utime)
            *(int64_t *)((char *)mb->scratch + mb->utime.offset) = now_us;
        const lcm_type_info_t *info = mb->type->info();
        int size = info->encoded_size(mb->scratch);
        uint8_t stackbuf[4096];
        uint8_t *buf = size <= (int)sizeof stackbuf ? stackbuf : malloc((size_t)size);
        if (buf && info->encode(buf, 0, size, mb->scratch) == size)
            lcm_publish(lcm, mb->channel, buf, (unsigned)size);
        if (buf != stackbuf)
            free(buf);
    }
}

uint64_t mgr_bindings_decode_errors(const mgr_bindings *b)
{
    uint64_t n = 0;
    for (int i = 0; i < b->n_msgs; i++)
        if (b->msgs[i].sub)
            n += rx_decode_errors(b->msgs[i].sub);
    return n;
}

int mgr_bindings_inputs_ready(const mgr_bindings *b)
{
    for (int i = 0; i < b->n_msgs; i++)
        if (b->msgs[i].sub && !b->msgs[i].optional && rx_stats(b->msgs[i].sub)->delivered == 0)
            return 0;
    return 1;
}

void mgr_bindings_free(mgr_bindings *b, lcm_t *lcm)
{
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (mb->sub)
            rx_unsubscribe(lcm, mb->sub);
        if (mb->is_output)
            free(mb->scratch);
        free(mb->vars);
    }
    free(b->msgs);
    memset(b, 0, sizeof *b);
}
