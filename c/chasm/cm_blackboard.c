/* The blackboard seen from outside (managers, tools) and from plugins. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chasm/cm_machine.h"

static cm_var *var_at(const chasm_machine *m, int id)
{
    return id >= 0 && id < m->n_vars ? &m->vars[id] : NULL;
}

int chasm_var_find(const chasm_machine *m, const char *name)
{
    cm_var *v = cm_map_get(&m->var_map, name);
    return v ? v->index : -1;
}
size_t chasm_var_count(const chasm_machine *m) { return (size_t)m->n_vars; }
const char *chasm_var_name(const chasm_machine *m, int id) { return var_at(m, id) ? m->vars[id].name : NULL; }
chasm_type chasm_var_type(const chasm_machine *m, int id) { return var_at(m, id) ? m->vars[id].type : CHASM_DOUBLE; }
chasm_var_kind chasm_var_kind_of(const chasm_machine *m, int id) { return var_at(m, id) ? m->vars[id].kind : CHASM_VAR_LOCAL; }
const char *chasm_var_unit(const chasm_machine *m, int id) { return var_at(m, id) ? m->vars[id].unit->name : ""; }

static cm_var *settable(chasm_machine *m, int id, chasm_type t)
{
    cm_var *v = var_at(m, id);
    return v && v->type == t ? v : NULL;
}

int chasm_var_set_double(chasm_machine *m, int id, double x, int64_t utime)
{
    cm_var *v = settable(m, id, CHASM_DOUBLE);
    if (!v) return -1;
    v->d = x;
    v->updated_us = utime;
    v->has_value = true;
    return 0;
}
int chasm_var_set_int(chasm_machine *m, int id, int64_t x, int64_t utime)
{
    cm_var *v = settable(m, id, CHASM_INT);
    if (!v) return -1;
    v->i = x;
    v->d = (double)x;
    v->updated_us = utime;
    v->has_value = true;
    return 0;
}
int chasm_var_set_bool(chasm_machine *m, int id, bool x, int64_t utime)
{
    cm_var *v = settable(m, id, CHASM_BOOL);
    if (!v) return -1;
    v->b = x;
    v->d = x;
    v->updated_us = utime;
    v->has_value = true;
    return 0;
}
int chasm_var_set_string(chasm_machine *m, int id, const char *x, int64_t utime)
{
    cm_var *v = settable(m, id, CHASM_STRING);
    if (!v || !x || strlen(x) >= v->s_cap) return -1;
    memcpy(v->s, x, strlen(x) + 1);
    v->updated_us = utime;
    v->has_value = true;
    return 0;
}
double chasm_var_get_double(const chasm_machine *m, int id) { return var_at(m, id) ? m->vars[id].d : 0.0; }
int64_t chasm_var_get_int(const chasm_machine *m, int id)
{
    cm_var *v = var_at(m, id);
    return !v ? 0 : v->type == CHASM_INT ? v->i : (int64_t)v->d;
}
bool chasm_var_get_bool(const chasm_machine *m, int id)
{
    cm_var *v = var_at(m, id);
    return v && (v->type == CHASM_BOOL ? v->b : v->d != 0);
}
const char *chasm_var_get_string(const chasm_machine *m, int id)
{
    cm_var *v = var_at(m, id);
    return v && v->type == CHASM_STRING ? v->s : "";
}
int64_t chasm_var_updated_us(const chasm_machine *m, int id) { return var_at(m, id) ? m->vars[id].updated_us : CM_NEVER; }

/* ---------------------------------------------------- plugin side (slots) */

static const cm_slot *slot(const chasm_ctx *c, int s, chasm_slot_kind want, chasm_type t)
{
    const cm_ext *x = c->engine;
    const cm_binding *b = x->b;
    if (s < 0 || s >= b->n_slots || b->specs[s].type != t) return NULL;
    chasm_slot_kind k = b->specs[s].kind;
    if (want == CHASM_PARAM ? k != CHASM_PARAM : (k == CHASM_PARAM || (want == CHASM_WRITES && k != CHASM_WRITES)))
        return NULL;
    if (want != CHASM_PARAM && !b->slots[s].var) return NULL;
    return &b->slots[s];
}

static double p_double(const chasm_ctx *c, int s) { const cm_slot *x = slot(c, s, CHASM_PARAM, CHASM_DOUBLE); return x ? x->d : 0.0; }
static int64_t p_int(const chasm_ctx *c, int s) { const cm_slot *x = slot(c, s, CHASM_PARAM, CHASM_INT); return x ? x->i : 0; }
static int p_bool(const chasm_ctx *c, int s) { const cm_slot *x = slot(c, s, CHASM_PARAM, CHASM_BOOL); return x ? x->b : 0; }
static const char *p_string(const chasm_ctx *c, int s) { const cm_slot *x = slot(c, s, CHASM_PARAM, CHASM_STRING); return x && x->s ? x->s : ""; }
static double r_double(const chasm_ctx *c, int s) { const cm_slot *x = slot(c, s, CHASM_READS, CHASM_DOUBLE); return x ? x->var->d : 0.0; }
static int64_t r_int(const chasm_ctx *c, int s) { const cm_slot *x = slot(c, s, CHASM_READS, CHASM_INT); return x ? x->var->i : 0; }
static int r_bool(const chasm_ctx *c, int s) { const cm_slot *x = slot(c, s, CHASM_READS, CHASM_BOOL); return x ? x->var->b : 0; }
static const char *r_string(const chasm_ctx *c, int s) { const cm_slot *x = slot(c, s, CHASM_READS, CHASM_STRING); return x ? x->var->s : ""; }

static double age(const chasm_ctx *c, int s)
{
    const cm_ext *x = c->engine;
    if (s < 0 || s >= x->b->n_slots || !x->b->slots[s].var) return 1e300;
    double a = cm_age_s(x->m, x->b->slots[s].var->updated_us, c->now_us);
    return isinf(a) ? 1e300 : a;
}

static cm_var *w(chasm_ctx *c, int s, chasm_type t)
{
    const cm_slot *x = slot(c, s, CHASM_WRITES, t);
    if (!x) return NULL;
    x->var->updated_us = c->now_us;
    x->var->has_value = true;
    return x->var;
}
static void w_double(chasm_ctx *c, int s, double v) { cm_var *x = w(c, s, CHASM_DOUBLE); if (x) x->d = v; }
static void w_int(chasm_ctx *c, int s, int64_t v) { cm_var *x = w(c, s, CHASM_INT); if (x) { x->i = v; x->d = (double)v; } }
static void w_bool(chasm_ctx *c, int s, int v) { cm_var *x = w(c, s, CHASM_BOOL); if (x) { x->b = v != 0; x->d = x->b; } }
static void w_string(chasm_ctx *c, int s, const char *v)
{
    if (v && strlen(v) > CHASM_STRING_MAX) { /* never cut: the write is refused, and said */
        const cm_ext *e = c->engine;
        cm_log(e->m, c->state_path, "string of %zu characters not written: the limit is %d", strlen(v), CHASM_STRING_MAX);
        return;
    }
    cm_var *x = w(c, s, CHASM_STRING);
    if (x) snprintf(x->s, x->s_cap, "%s", v ? v : "");
}

static void plog(chasm_ctx *c, const char *msg)
{
    const cm_ext *x = c->engine;
    cm_log(x->m, c->state_path, "%s", msg ? msg : "");
}

/* Message variables (cm_stream.h). A slot of the wrong kind or type gives
 * NULL / a refusal, like reads of the wrong type give 0. */
static const void *next_msg(chasm_ctx *c, int s, size_t *len)
{
    const cm_ext *x = c->engine;
    if (len) *len = 0;
    if (!slot(c, s, CHASM_READS, CHASM_MESSAGES) || x->b->specs[s].kind != CHASM_READS) return NULL;
    cm_slot *sl = &x->b->slots[s];
    return cm_stream_next(sl->var->stream, &sl->next_msg, len);
}

static int post_msg(chasm_ctx *c, int s, const void *d, size_t n)
{
    const cm_ext *x = c->engine;
    const cm_slot *sl = slot(c, s, CHASM_WRITES, CHASM_MESSAGES);
    if (!sl) {
        /* a slot that is no messages output: refused, and counted where it can be */
        if (s >= 0 && s < x->b->n_slots && x->b->slots[s].var && x->b->slots[s].var->stream)
            x->b->slots[s].var->stream->refused++;
        return -1;
    }
    if (cm_stream_post(sl->var->stream, d, n)) {
        if (sl->var->stream->refused == 1) /* said once; the count is in the status */
            cm_log(x->m, c->state_path, "a message posted to '%s' was refused (%zu bytes; at most %d bytes and %u per cycle)",
                   sl->var->name, n, CHASM_MESSAGE_MAX_BYTES, sl->var->stream->capacity);
        return -1;
    }
    return 0;
}

/* A parameter the plan gave, or a variable slot with a variable bound. */
static int given(const chasm_ctx *c, int s)
{
    const cm_ext *x = c->engine;
    if (s < 0 || s >= x->b->n_slots) return 0;
    return x->b->specs[s].kind == CHASM_PARAM ? x->b->slots[s].given : x->b->slots[s].var != NULL;
}

const chasm_host_api cm_host_api = {p_double, p_int, p_bool, p_string, r_double, r_int, r_bool, r_string, age,
                                    w_double, w_int, w_bool, w_string, plog, next_msg, post_msg, given};
