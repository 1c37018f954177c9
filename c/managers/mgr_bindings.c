#include "managers/mgr_bindings.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The file a binding's line is in: an included file's lines name it. */
static const char *file_of(const mgr_message_binding *mb, const char *path) { return mb->file ? mb->file : path; }

/* A messages variable is bound by a line whose prefix is its whole name. */
static int bind_stream(mgr_bindings *b, const char *path, int var, mgr_errors *errs)
{
    const char *name = chasm_var_name(b->machine, var);
    chasm_var_kind kind = chasm_var_kind_of(b->machine, var);
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (strcmp(mb->prefix, name))
            continue;
        if (mb->is_output != (kind == CHASM_VAR_OUTPUT)) {
            mgr_errors_add(errs, "%s:%d:1: plan %s '%s' is bound as an %s", file_of(mb, path), mb->line,
                    kind == CHASM_VAR_OUTPUT ? "output" : "input", name, mb->is_output ? "output" : "input");
            return 1;
        }
        mb->stream_var = var;
        return 0;
    }
    mgr_errors_add(errs, "%s:1:1: plan %s '%s' (messages) has no binding (no `%s %s CHANNEL TYPE` line)", path,
            kind == CHASM_VAR_OUTPUT ? "output" : "input", name, kind == CHASM_VAR_OUTPUT ? "output" : "input", name);
    return 1;
}

static int bind_var(mgr_bindings *b, const char *path, int var, mgr_errors *errs)
{
    const char *name = chasm_var_name(b->machine, var);
    chasm_var_kind kind = chasm_var_kind_of(b->machine, var);
    if (chasm_var_type(b->machine, var) == CHASM_MESSAGES)
        return bind_stream(b, path, var, errs);
    const char *dot = strchr(name, '.');
    size_t plen = dot ? (size_t)(dot - name) : 0;
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (!dot || strlen(mb->prefix) != plen || strncmp(mb->prefix, name, plen))
            continue;
        if (mb->is_output != (kind == CHASM_VAR_OUTPUT)) {
            mgr_errors_add(errs, "%s:%d:1: plan %s '%s' is bound as an %s", file_of(mb, path), mb->line,
                    kind == CHASM_VAR_OUTPUT ? "output" : "input", name, mb->is_output ? "output" : "input");
            return 1;
        }
        mgr_var_binding vb = {var, chasm_var_type(b->machine, var), {0, 0}};
        char err[256];
        if (field_path_resolve(mb->type, dot + 1, &vb.field, err, sizeof err) != 0) {
            mgr_errors_add(errs, "%s:%d:1: plan variable '%s': %s", file_of(mb, path), mb->line, name, err);
            return 1;
        }
        if ((vb.var_type == CHASM_STRING) != !field_ref_is_numeric(&vb.field)) {
            mgr_errors_add(errs, "%s:%d:1: plan variable '%s' is %s but the field is %s", file_of(mb, path),
                    mb->line, name,
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
    mgr_errors_add(errs, "%s:1:1: plan %s '%s' has no binding (no `%s %.*s ...` line)", path,
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

static int bind_all(mgr_bindings *b, const char *path, chasm_machine *m, mgr_errors *errs, int errors);

int mgr_bindings_load(mgr_bindings *b, const char *path, const char *vehicle, chasm_machine *m, mgr_errors *errs)
{
    memset(b, 0, sizeof *b);
    b->machine = m;
    b->vehicle = vehicle;
    return bind_all(b, path, m, errs, mgr_bindings_parse_file(b, path, vehicle, errs));
}

int mgr_bindings_load_text(mgr_bindings *b, const char *path, const char *text, size_t len, const char *vehicle,
                           chasm_machine *m, mgr_errors *errs)
{
    memset(b, 0, sizeof *b);
    b->machine = m;
    b->vehicle = vehicle;
    return bind_all(b, path, m, errs, mgr_bindings_parse_text(b, path, text, len, vehicle, errs));
}

static int bind_all(mgr_bindings *b, const char *path, chasm_machine *m, mgr_errors *errs, int errors)
{
    for (int i = 0; i < b->n_msgs; i++)
        b->msgs[i].stream_var = -1;
    for (size_t v = 0; v < chasm_var_count(m); v++)
        if (chasm_var_kind_of(m, (int)v) != CHASM_VAR_LOCAL)
            errors += bind_var(b, path, (int)v, errs);
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        char err[128];
        if (mb->stream_var >= 0 && mb->n_vars) {
            /* one line, one meaning: whole messages, or fields, not both */
            mgr_errors_add(errs, "%s:%d:1: '%s' carries whole messages (plan variable '%s' is messages): it cannot "
                    "also bind the field variable '%s'", file_of(mb, path), mb->line, mb->prefix, mb->prefix,
                    chasm_var_name(m, mb->vars[0].var));
            errors++;
        }
        if (mb->on_change && mb->stream_var >= 0) {
            /* a stream's messages are events: each one is published */
            mgr_errors_add(errs, "%s:%d:1: '%s' carries whole messages: `on_change` is for outputs of fields",
                    file_of(mb, path), mb->line, mb->prefix);
            errors++;
        }
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
        if (mb->is_output || (mb->n_vars == 0 && mb->stream_var < 0))
            continue;
        mb->owner = b;
        mb->sub = rx_subscribe(lcm, mb->channel, mb->type, mgr_input_received, mb);
        if (!mb->sub)
            return -1;
        if (mb->stream_var >= 0) {
            /* a burst between two cycles must reach the stream, not die in
             * liblcm's queue (30 by default, dropping the newest) */
            chasm_messages_info mi;
            if (chasm_messages_stats(b->machine, mb->stream_var, &mi) == 0 && mi.capacity > 30)
                rx_set_queue_capacity(mb->sub, (int)mi.capacity);
        }
    }
    return 0;
}

/* Every message posted to an output stream this cycle, in order: published
 * as posted when it decodes as the bound type, refused and counted if not. */
static void publish_stream(mgr_bindings *b, mgr_message_binding *mb, lcm_t *lcm)
{
    size_t len;
    const void *raw;
    while ((raw = chasm_messages_take(b->machine, mb->stream_var, &len)) != NULL) {
        int rc = len <= INT32_MAX ? rx_decode(mb->type, raw, (int)len, mb->scratch) : -1;
        if (rc != 0) {
            if (mb->posts_refused++ == 0)
                fprintf(stderr, "%s: %s: refused a %zu-byte message posted to '%s': %s %s; further refusals are only "
                                "counted\n", b->who ? b->who : "manager", mb->channel, len,
                        chasm_var_name(b->machine, mb->stream_var),
                        rc == -1 ? "not a message of type (fingerprint)" : "truncated or malformed as",
                        mb->type->lcm_name);
            continue;
        }
        mb->type->info()->decode_cleanup(mb->scratch);
        memset(mb->scratch, 0, mb->type->struct_size);
        lcm_publish(lcm, mb->channel, raw, (unsigned)len);
        mb->messages_out++;
    }
}

mgr_stream_counts mgr_bindings_stream_counts(const mgr_bindings *b)
{
    mgr_stream_counts c = {0};
    for (int i = 0; i < b->n_msgs; i++) {
        const mgr_message_binding *mb = &b->msgs[i];
        if (mb->stream_var < 0)
            continue;
        chasm_messages_info mi = {0};
        if (b->machine)
            chasm_messages_stats(b->machine, mb->stream_var, &mi);
        c.n_streams++;
        c.in += mb->messages_in;
        c.out += mb->messages_out;
        c.missed += mi.missed;
        c.refused += mb->posts_refused + mi.refused;
    }
    return c;
}

/* `on_change`: whether the output, filled for this cycle, differs from the
 * last one published (its utime aside), or a second of mission time passed
 * since (so a listener that joins late, or checks its age, still hears it).
 * Remembers what it says goes out; memory is only taken then, never on the
 * cycles that publish nothing. Out of memory: publish every cycle. */
static int changed_or_due(mgr_message_binding *mb, int64_t now_us)
{
    if (mb->has_utime)
        *(int64_t *)((char *)mb->scratch + mb->utime.offset) = 0;
    const lcm_type_info_t *info = mb->type->info();
    int size = info->encoded_size(mb->scratch);
    uint8_t stackbuf[4096];
    uint8_t *enc = size <= (int)sizeof stackbuf ? stackbuf : malloc((size_t)size);
    int due = 1;
    if (enc && info->encode(enc, 0, size, mb->scratch) == size) {
        int same = mb->last_sent && mb->last_sent_len == size && !memcmp(mb->last_sent, enc, (size_t)size);
        due = !same || now_us - mb->last_sent_us >= MGR_ON_CHANGE_PERIOD_US || now_us < mb->last_sent_us;
        uint8_t *keep = due && !same ? realloc(mb->last_sent, (size_t)size) : mb->last_sent;
        if (keep && due) {
            if (!same)
                memcpy(keep, enc, (size_t)size);
            mb->last_sent = keep;
            mb->last_sent_len = size;
            mb->last_sent_us = now_us;
        }
    }
    if (enc != stackbuf)
        free(enc);
    return due;
}

void mgr_bindings_publish(mgr_bindings *b, lcm_t *lcm, int64_t now_us)
{
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (mb->is_output && mb->stream_var >= 0) {
            publish_stream(b, mb, lcm);
            continue;
        }
        if (!mb->is_output || mb->n_vars == 0)
            continue;
        for (int k = 0; k < mb->n_vars; k++) {
            const mgr_var_binding *v = &mb->vars[k];
            if (v->var_type == CHASM_STRING)
                *(const char **)((char *)mb->scratch + v->field.offset) = chasm_var_get_string(b->machine, v->var);
            else
                field_ref_set_double(&v->field, mb->scratch, chasm_var_get_double(b->machine, v->var));
        }
        if (mb->on_change && !changed_or_due(mb, now_us))
            continue;
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

void mgr_bindings_free(mgr_bindings *b, lcm_t *lcm)
{
    for (int i = 0; i < b->n_msgs; i++) {
        mgr_message_binding *mb = &b->msgs[i];
        if (mb->sub)
            rx_unsubscribe(lcm, mb->sub);
        if (mb->is_output)
            free(mb->scratch);
        free(mb->last_sent);
        free(mb->vars);
        free(mb->prefix);
        free(mb->file);
    }
    free(b->msgs);
    mgr_held_free(&b->held);
    memset(b, 0, sizeof *b);
}
