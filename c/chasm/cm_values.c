/* Written values -> typed, unit-converted slots; variables by name. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chasm/cm_compile.h"

const char *cm_type_name(chasm_type t)
{
    static const char *n[] = {"double", "int", "bool", "string", "messages"};
    return (unsigned)t < 5 ? n[t] : "?";
}

static const char *written(const cm_aval *v, char *buf, size_t n)
{
    switch (v->kind) {
    case V_NUMBER: snprintf(buf, n, "%g%s%s", v->num, v->unit ? " " : "", v->unit ? v->unit->name : ""); break;
    case V_STRING: snprintf(buf, n, "\"%s\"", v->str); break;
    case V_BOOL: snprintf(buf, n, "%s", v->b ? "true" : "false"); break;
    case V_NAME: snprintf(buf, n, "'%s'", v->str); break;
    default: snprintf(buf, n, "nothing"); break;
    }
    return buf;
}

int cm_value(cm_cc *cc, const cm_aval *v0, chasm_type type, const cm_unit *unit, const char *what, cm_slot *out)
{
    const cm_aval *v = v0;
    char via[160] = "";
    if (v->kind == V_NONE) return -1; /* parse error already reported */
    if (v->kind == V_PARAM) {
        cm_aparam *p = cm_map_get(&cc->m->param_map, v->str);
        if (!p) {
            cm_suggest s;
            cm_suggest_init(&s, v->str);
            for (cm_aparam *q = cc->plan->params; q; q = q->next) cm_suggest_add(&s, q->name);
            char h[96];
            const char *hint = cm_suggest_hint(&s, h, sizeof h);
            cm_error(cc->d, v->loc, "unknown parameter '$%s'%s", v->str,
                     *hint ? hint : " (declare it with `param NAME = VALUE`)");
            return -1;
        }
        snprintf(via, sizeof via, " (from $%s)", v->str);
        v = &p->val;
    }
    char b[96];
    const cm_loc at = v0->loc;
    switch (type) {
    case CHASM_DOUBLE:
    case CHASM_INT:
        if (v->kind != V_NUMBER) {
            cm_error(cc->d, at, "%s must be a number, not %s%s", what, written(v, b, sizeof b), via);
            return -1;
        }
        if (type == CHASM_INT && !v->is_int) {
            cm_error(cc->d, at, "%s must be a whole number, not %s%s", what, written(v, b, sizeof b), via);
            return -1;
        }
        if (unit && unit->dim != CM_DIM_NONE) {
            if (!v->unit) {
                cm_error(cc->d, at, "%s needs a unit: it is %s (write e.g. '%g %s')%s", what, cm_dim_name(unit->dim),
                         v->num, unit->name, via);
                return -1;
            }
            if (v->unit->dim != unit->dim) {
                cm_error(cc->d, at, "%s is %s (%s), but '%s' is %s%s", what, cm_dim_name(unit->dim), unit->name,
                         v->unit->name, cm_dim_name(v->unit->dim), via);
                return -1;
            }
            out->d = v->num * v->unit->to_si / unit->to_si;
        } else {
            if (v->unit) {
                cm_error(cc->d, at, "%s is a plain number, without a unit ('%s' given)%s", what, v->unit->name, via);
                return -1;
            }
            out->d = v->num;
        }
        if (type == CHASM_INT) {
            if (!(fabs(out->d) < 9.0e18)) {
                cm_error(cc->d, at, "%s is out of the integer range%s", what, via);
                return -1;
            }
            out->i = (int64_t)out->d;
        }
        if (!isfinite(out->d)) {
            cm_error(cc->d, at, "%s is not a finite number%s", what, via);
            return -1;
        }
        return 0;
    case CHASM_BOOL:
        if (v->kind != V_BOOL) {
            cm_error(cc->d, at, "%s must be true or false, not %s%s", what, written(v, b, sizeof b), via);
            return -1;
        }
        out->b = v->b;
        out->d = v->b;
        return 0;
    case CHASM_STRING:
        if (v->kind != V_STRING) {
            cm_error(cc->d, at, "%s must be a string in quotes, not %s%s", what, written(v, b, sizeof b), via);
            return -1;
        }
        if (strlen(v->str) > CHASM_STRING_MAX) {
            cm_error(cc->d, at, "%s is a string of %zu characters: strings hold at most %d (CHASM_STRING_MAX)%s", what,
                     strlen(v->str), CHASM_STRING_MAX, via);
            return -1;
        }
        out->s = v->str;
        return 0;
    case CHASM_MESSAGES:
        cm_error(cc->d, at, "%s is a stream of messages: it has no value to give%s", what, via);
        return -1;
    }
    return -1;
}

int cm_duration(cm_cc *cc, const cm_aval *v, const char *what, int64_t *us)
{
    cm_slot s = {0};
    if (cm_value(cc, v, CHASM_DOUBLE, cm_unit_find("s"), what, &s)) return -1;
    if (s.d < 0 || s.d > 1e9) {
        cm_error(cc->d, v->loc, "%s must be between 0 s and 1e9 s", what);
        return -1;
    }
    *us = (int64_t)llround(s.d * 1e6);
    return 0;
}

cm_var *cm_find_var(cm_cc *cc, const char *name, cm_loc loc, const char *what)
{
    cm_var *v = cm_map_get(&cc->m->var_map, name);
    if (v) return v;
    cm_suggest s;
    cm_suggest_init(&s, name);
    for (int i = 0; i < cc->m->n_vars; i++) cm_suggest_add(&s, cc->m->vars[i].name);
    char h[96];
    const char *hint = cm_suggest_hint(&s, h, sizeof h);
    cm_error(cc->d, loc, "unknown variable '%s' in %s%s", name, what,
             *hint ? hint : " (declare it with `input`, `output` or `var`)");
    return NULL;
}

void cm_add_writer(cm_cc *cc, cm_var *v, cm_loc loc, const char *desc, cm_state *state)
{
    int i = v->index;
    if (cc->n_writers[i] == cc->cap_writers[i]) {
        int nc = cc->cap_writers[i] ? cc->cap_writers[i] * 2 : 4;
        cm_writer *w = cm_alloc(cc->a, sizeof *w * (size_t)nc);
        if (cc->n_writers[i]) memcpy(w, cc->writers[i], sizeof *w * (size_t)cc->n_writers[i]);
        cc->writers[i] = w;
        cc->cap_writers[i] = nc;
    }
    cc->writers[i][cc->n_writers[i]++] = (cm_writer){loc, desc, state};
}

static int on_same_path(const cm_state *a, const cm_state *b)
{
    /* Can both be active at once? Only if one is an ancestor-or-self of the other. */
    const cm_state *x = a->depth >= b->depth ? a : b, *y = a->depth >= b->depth ? b : a;
    while (x && x->depth > y->depth) x = x->parent;
    return x == y;
}

static const char *loc_str(cm_cc *cc, cm_loc l)
{
    return cm_sprintf(cc->a, "%s:%d:%d", l.file, l.line, l.col);
}

/* One writer per variable: the vehicle writes inputs and nothing else may;
 * two actions may write one variable only if their states can never be
 * active together (different branches of the forest). */
void cm_check_writers(cm_cc *cc)
{
    for (int i = 0; i < cc->m->n_vars; i++) {
        cm_var *v = &cc->m->vars[i];
        int n = cc->n_writers[i];
        cm_writer *w = cc->writers[i];
        for (int j = 0; j < n; j++) {
            if (v->kind == CHASM_VAR_INPUT) {
                cm_error(cc->d, w[j].loc,
                         "variable '%s' has two writers: it is an input, written by the vehicle (declared at %s), "
                         "and %s writes it",
                         v->name, loc_str(cc, v->loc), w[j].desc);
                continue;
            }
            for (int k = 0; k < j; k++) {
                if (on_same_path(w[j].state, w[k].state)) {
                    cm_error(cc->d, w[j].loc, "variable '%s' has two writers active at once: %s (at %s) and %s",
                             v->name, w[k].desc, loc_str(cc, w[k].loc), w[j].desc);
                    break;
                }
            }
        }
    }
}

/* A messages variable: its capacity (`messages(N)`, default 64) and stream. */
static int compile_stream(cm_cc *cc, const cm_avar *a, cm_var *v)
{
    int64_t cap = CHASM_MESSAGES_DEFAULT_CAPACITY;
    if (a->has_capacity) {
        cm_slot s = {0};
        char what[160];
        snprintf(what, sizeof what, "the capacity of '%s'", a->name);
        if (cm_value(cc, &a->capacity, CHASM_INT, NULL, what, &s)) return -1;
        if (s.i < 1 || s.i > CHASM_MESSAGES_MAX_CAPACITY) {
            cm_error(cc->d, a->capacity.loc, "%s is %lld messages, outside [1, %d]", what, (long long)s.i,
                     CHASM_MESSAGES_MAX_CAPACITY);
            return -1;
        }
        cap = s.i;
    }
    v->stream = cm_stream_new(cc->m, v, (uint32_t)cap);
    if (!v->stream) {
        cm_error(cc->d, a->loc, "out of memory for the %lld messages of '%s'", (long long)cap, a->name);
        return -1;
    }
    return 0;
}

void cm_compile_vars(cm_cc *cc)
{
    chasm_machine *m = cc->m;
    int n = 0;
    for (cm_avar *a = cc->plan->vars; a; a = a->next) n++;
    m->vars = cm_alloc(cc->a, sizeof *m->vars * (size_t)(n ? n : 1));
    for (cm_avar *a = cc->plan->vars; a; a = a->next) {
        cm_var *prev = cm_map_get(&m->var_map, a->name);
        if (prev) {
            cm_error(cc->d, a->loc, "variable '%s' is declared twice (first at %s)", a->name, loc_str(cc, prev->loc));
            continue;
        }
        cm_var *v = &m->vars[m->n_vars];
        v->index = m->n_vars;
        v->name = a->name;
        v->kind = (chasm_var_kind)a->kind;
        v->loc = a->loc;
        v->unit = a->unit ? a->unit : cm_unit_find("");
        v->updated_us = CM_NEVER;
        const char *tn[] = {"double", "int", "bool", "string", "messages"};
        int t = -1;
        for (int k = 0; k < 5; k++)
            if (!strcmp(a->type_name, tn[k])) t = k;
        if (t < 0) {
            cm_suggest s;
            cm_suggest_init(&s, a->type_name);
            for (int k = 0; k < 5; k++) cm_suggest_add(&s, tn[k]);
            if (!strcmp(a->type_name, "float") || !strcmp(a->type_name, "real")) s.best = "double";
            if (!strcmp(a->type_name, "boolean")) s.best = "bool";
            char h[96];
            const char *hint = cm_suggest_hint(&s, h, sizeof h);
            cm_error(cc->d, a->type_loc, "unknown type '%s' for variable '%s'%s", a->type_name, a->name,
                     *hint ? hint : " (types: double, int, bool, string, messages)");
            continue;
        }
        v->type = (chasm_type)t;
        if (v->type != CHASM_DOUBLE && a->unit && a->unit->dim != CM_DIM_NONE) {
            cm_error(cc->d, a->type_loc, "only double variables carry a unit ('%s' is %s)", a->name, a->type_name);
            continue;
        }
        if (a->has_capacity && v->type != CHASM_MESSAGES) {
            cm_error(cc->d, a->cap_loc, "only messages variables have a capacity ('%s' is %s)", a->name, a->type_name);
            continue;
        }
        if (v->type == CHASM_MESSAGES && compile_stream(cc, a, v)) continue;
        if (v->type == CHASM_STRING) {
            v->s_cap = CHASM_STRING_MAX + 1;
            v->s = cm_alloc(cc->a, v->s_cap);
        }
        if (a->has_init) {
            cm_slot s = {0};
            char what[160];
            snprintf(what, sizeof what, "the initial value of '%s'", a->name);
            if (!cm_value(cc, &a->init, v->type, v->unit, what, &s)) {
                v->d = s.d;
                v->i = s.i;
                v->b = s.b;
                if (v->type == CHASM_STRING) snprintf(v->s, v->s_cap, "%s", s.s);
                if (v->type == CHASM_INT) v->d = (double)s.i;
                v->has_value = true;
            }
        }
        cm_map_put(&m->var_map, v->name, v);
        m->n_vars++;
    }
    cc->writers = cm_alloc(cc->a, sizeof *cc->writers * (size_t)(m->n_vars + 1));
    cc->n_writers = cm_alloc(cc->a, sizeof(int) * (size_t)(m->n_vars + 1));
    cc->cap_writers = cm_alloc(cc->a, sizeof(int) * (size_t)(m->n_vars + 1));
}
