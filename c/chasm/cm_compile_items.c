/* Tests and actions of every state (and the plan's global tests). */
#include <stdio.h>
#include <string.h>

#include "chasm/cm_compile.h"

static const char *op_text(cm_cmp op)
{
    static const char *t[] = {"<", "<=", ">", ">=", "==", "!="};
    return t[op];
}

static void compile_test(cm_cc *cc, const cm_atest *a, cm_state *owner, cm_test *t)
{
    const cm_acrit *c = &a->crit;
    t->name = a->name;
    t->state = owner;
    t->kind = c->kind;
    t->op = c->op;
    t->loc = a->loc;
    t->ast = a;
    t->true_since = CM_NEVER;
    char what[256];
    if (c->has_hold) {
        snprintf(what, sizeof what, "'for' of test '%s'", a->name);
        cm_duration(cc, &c->hold, what, &t->hold_us);
    }
    switch (c->kind) {
    case CR_ELAPSED:
    case CR_AGE: {
        if (c->kind == CR_AGE) {
            snprintf(what, sizeof what, "test '%s'", a->name);
            t->var = cm_find_var(cc, c->var, c->var_loc, what);
        }
        int64_t us = 0;
        snprintf(what, sizeof what, "the duration in test '%s'", a->name);
        if (!cm_duration(cc, &c->value, what, &us)) t->value = (double)us * 1e-6;
        return;
    }
    case CR_HANDLER: {
        const void *spec = NULL;
        cm_plugin *p = cm_find_plugin_of(cc, c->handler, 1, c->var_loc, &spec);
        if (!p) return;
        const chasm_test_spec *ts = spec;
        t->cur = cm_bind(cc, cc->a, p->current, c->handler, ts->params, ts->n_params, c->args, c->var_loc, owner, false);
        if (t->cur) {
            t->cur->test = ts;
            t->cur->ver->refs++;
        }
        return;
    }
    default: break;
    }
    snprintf(what, sizeof what, "test '%s'", a->name);
    cm_var *v = t->var = cm_find_var(cc, c->var, c->var_loc, what);
    if (!v) return;
    t->angle = v->unit->dim == CM_DIM_ANGLE;
    if (v->type == CHASM_MESSAGES) {
        cm_error(cc->d, c->var_loc, "test '%s': '%s' is a stream of messages, it has no value to compare: test its age "
                 "('age %s < 10 s') or read it in a behavior", a->name, v->name, v->name);
        return;
    }
    if (c->kind == CR_BOOLVAR) {
        if (v->type != CHASM_BOOL)
            cm_error(cc->d, c->var_loc, "test '%s': '%s' is %s, not bool: compare it (e.g. '%s > 0')", a->name, v->name,
                     cm_type_name(v->type), v->name);
        return;
    }
    cm_slot s = {0};
    snprintf(what, sizeof what, "the value compared with '%s'", v->name);
    if (v->type == CHASM_BOOL || v->type == CHASM_STRING) {
        if (c->kind == CR_WITHIN || c->has_tol) {
            cm_error(cc->d, c->loc, "test '%s': a tolerance needs a number variable, '%s' is %s", a->name, v->name,
                     cm_type_name(v->type));
            return;
        }
        if (c->op != OP_EQ && c->op != OP_NE) {
            cm_error(cc->d, c->loc, "test '%s': '%s' is %s and can only be compared with == or != (not %s)", a->name,
                     v->name, cm_type_name(v->type), op_text(c->op));
            return;
        }
        if (!cm_value(cc, &c->value, v->type, NULL, what, &s)) {
            t->value = s.b;
            t->sval = s.s;
        }
        return;
    }
    if (!cm_value(cc, &c->value, CHASM_DOUBLE, v->unit, what, &s)) t->value = s.d;
    if (c->has_tol) {
        snprintf(what, sizeof what, "the tolerance on '%s'", v->name);
        cm_slot tol = {0};
        if (!cm_value(cc, &c->tol, CHASM_DOUBLE, v->unit, what, &tol)) {
            if (tol.d < 0) cm_error(cc->d, c->tol.loc, "test '%s': a tolerance cannot be negative", a->name);
            t->tol = tol.d;
            t->has_tol = true;
        }
    }
}

static void add_tests(cm_cc *cc, const cm_atest *list, cm_state *owner, cm_test **arr, int *n)
{
    int cnt = 0;
    for (const cm_atest *a = list; a; a = a->next) cnt++;
    *arr = cm_alloc(cc->a, sizeof **arr * (size_t)(cnt ? cnt : 1));
    for (const cm_atest *a = list; a; a = a->next) {
        char *key = cm_sprintf(cc->a, "%s:%s", owner ? owner->path : "", a->name);
        cm_test *t = &(*arr)[*n];
        cm_test *dup = cm_map_put(&cc->test_map, key, t);
        if (dup) {
            if (owner)
                cm_error(cc->d, a->loc, "test '%s' is defined twice in state '%s' (first at %s:%d:%d)", a->name,
                         owner->name, dup->loc.file, dup->loc.line, dup->loc.col);
            else
                cm_error(cc->d, a->loc, "test '%s' is defined twice at the top level (first at %s:%d:%d)", a->name,
                         dup->loc.file, dup->loc.line, dup->loc.col);
            continue;
        }
        compile_test(cc, a, owner, t);
        (*n)++;
    }
    cc->m->n_tests_total += (size_t)*n;
}

void cm_compile_tests(cm_cc *cc)
{
    chasm_machine *m = cc->m;
    add_tests(cc, cc->plan->tests, NULL, &m->globals, &m->n_globals);
    for (int i = 0; i < m->n_states; i++) {
        cm_state *s = &m->states[i];
        add_tests(cc, s->ast->tests, s, &s->tests, &s->n_tests);
    }
}

static void compile_action(cm_cc *cc, const cm_aaction *a, cm_state *s, cm_action *x)
{
    x->state = s;
    x->tm = a->tm;
    x->loc = a->loc;
    x->ast = a;
    char what[256];
    if (a->tm == TM_EVERY || a->tm == TM_AFTER) {
        snprintf(what, sizeof what, "the period of '%s'", a->is_set ? "set" : a->behavior);
        if (!cm_duration(cc, &a->period, what, &x->period_us) && a->tm == TM_EVERY && x->period_us <= 0)
            cm_error(cc->d, a->period.loc, "'every' needs a period above 0 s (use 'every cycle' to run each cycle)");
    }
    if (a->is_set) {
        x->kind = ACT_SET;
        x->text = cm_sprintf(cc->a, "set %s", a->set_var);
        snprintf(what, sizeof what, "'set'");
        cm_var *v = x->var = cm_find_var(cc, a->set_var, a->set_var_loc, what);
        if (!v) return;
        snprintf(what, sizeof what, "the value set to '%s'", v->name);
        if (a->set_val.kind == V_NAME) {
            cm_error(cc->d, a->set_val.loc, "%s must be a constant ('set' copies no variables), not '%s'", what,
                     a->set_val.str);
            return;
        }
        if (!cm_value(cc, &a->set_val, v->type, v->unit, what, &x->value) && v->type == CHASM_INT)
            x->value.d = (double)x->value.i;
        cm_add_writer(cc, v, a->set_var_loc, cm_sprintf(cc->a, "'set' in state '%s'", s->path), s);
        return;
    }
    x->kind = ACT_PLUGIN;
    x->text = a->behavior;
    const void *spec = NULL;
    cm_plugin *p = cm_find_plugin_of(cc, a->behavior, 0, a->beh_loc, &spec);
    if (!p) return;
    const chasm_behavior_spec *bs = spec;
    x->cur = cm_bind(cc, cc->a, p->current, a->behavior, bs->params, bs->n_params, a->args, a->beh_loc, s, true);
    if (!x->cur) return;
    x->cur->beh = bs;
    x->cur->inst_size = bs->state_size;
    x->cur->inst = bs->state_size ? cm_alloc(cc->a, bs->state_size) : NULL;
    x->cur->ver->refs++;
}

void cm_compile_actions(cm_cc *cc)
{
    chasm_machine *m = cc->m;
    for (int i = 0; i < m->n_states; i++) {
        cm_state *s = &m->states[i];
        int n = 0;
        for (cm_aaction *a = s->ast->actions; a; a = a->next) n++;
        s->actions = cm_alloc(cc->a, sizeof *s->actions * (size_t)(n ? n : 1));
        for (cm_aaction *a = s->ast->actions; a; a = a->next) compile_action(cc, a, s, &s->actions[s->n_actions++]);
    }
}
