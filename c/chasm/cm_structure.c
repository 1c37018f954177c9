/* What a loaded plan is made of, for views (chasm_structure.h): states,
 * actions, transitions, parameters, and the live values of the tests that
 * decide whether the active states move on. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chasm/chasm_structure.h"
#include "chasm/cm_machine.h"

static chasm_where where_of(cm_loc l) { return (chasm_where){l.file ? l.file : "", l.line, l.col}; }
static int index_of(const cm_state *s) { return s ? s->index : -1; }

const char *chasm_plan_name(const chasm_machine *m) { return m->plan_name ? m->plan_name : ""; }
int chasm_initial_state(const chasm_machine *m) { return index_of(m->initial); }
int chasm_abort_count(const chasm_machine *m) { return m->n_aborts; }

int chasm_state_info_get(const chasm_machine *m, int i, chasm_state_info *o)
{
    if (i < 0 || i >= m->n_states) return -1;
    const cm_state *s = &m->states[i];
    *o = (chasm_state_info){
        .name = s->name,
        .path = s->path,
        .parent = index_of(s->parent),
        .default_child = index_of(s->default_child),
        .next = index_of(s->next),
        .next_done = s->next_done,
        .n_actions = s->n_actions,
        .n_transitions = s->n_trans,
        .where = where_of(s->loc),
    };
    return 0;
}

int chasm_action_info_get(const chasm_machine *m, int i, int k, chasm_action_info *o)
{
    static const char *const models[] = {"entry", "exit", "cycle", "every", "after"};
    if (i < 0 || i >= m->n_states || k < 0 || k >= m->states[i].n_actions) return -1;
    const cm_action *a = &m->states[i].actions[k];
    *o = (chasm_action_info){
        .text = a->text ? a->text : "",
        .time_model = (unsigned)a->tm < 5 ? models[a->tm] : "?",
        .period_s = (double)a->period_us * 1e-6,
        .where = where_of(a->loc),
    };
    return 0;
}

int chasm_trans_info_get(const chasm_machine *m, int i, int k, chasm_trans_info *o)
{
    const cm_trans *t;
    if (i == -1) {
        if (k < 0 || k >= m->n_aborts) return -1;
        t = &m->aborts[k];
    } else {
        if (i < 0 || i >= m->n_states || k < 0 || k >= m->states[i].n_trans) return -1;
        t = &m->states[i].trans[k];
    }
    memset(o, 0, sizeof *o);
    o->from = index_of(t->owner);
    o->to = index_of(t->target);
    o->history = (int)t->history;
    o->condition = t->text ? t->text : "";
    o->n_tests = t->n_refs < CHASM_TRANS_MAX_TESTS ? t->n_refs : CHASM_TRANS_MAX_TESTS;
    for (int r = 0; r < o->n_tests; r++)
        o->test_name[r] = t->refs[r]->name;
    o->where = where_of(t->loc);
    return 0;
}

/* The definition of a parameter that won is the one its name maps to. */
static const cm_aparam *winner_at(const chasm_machine *m, size_t i)
{
    size_t n = 0;
    for (const cm_aparam *p = m->plan ? m->plan->params : NULL; p; p = p->next)
        if (cm_map_get(&m->param_map, p->name) == p && n++ == i) return p;
    return NULL;
}

size_t chasm_param_count(const chasm_machine *m)
{
    size_t n = 0;
    for (const cm_aparam *p = m->plan ? m->plan->params : NULL; p; p = p->next)
        n += cm_map_get(&m->param_map, p->name) == p;
    return n;
}

const char *chasm_param_get(const chasm_machine *m, size_t i, char *buf, size_t cap)
{
    const cm_aparam *p = winner_at(m, i);
    if (!p || !cap) return NULL;
    const cm_aval *v = &p->val;
    switch (v->kind) {
    case V_NUMBER:
        snprintf(buf, cap, "%.10g%s%s", v->num, v->unit && v->unit->name[0] ? " " : "", v->unit ? v->unit->name : "");
        break;
    case V_STRING: snprintf(buf, cap, "\"%s\"", v->str ? v->str : ""); break;
    case V_BOOL: snprintf(buf, cap, "%s", v->b ? "true" : "false"); break;
    default: snprintf(buf, cap, "%s", v->str ? v->str : ""); break;
    }
    return p->name;
}

static int add_trans_tests(const cm_trans *t, int n, bool *out, int cap)
{
    int k = t->n_refs < CHASM_TRANS_MAX_TESTS ? t->n_refs : CHASM_TRANS_MAX_TESTS;
    for (int r = 0; r < k; r++, n++)
        if (n < cap) out[n] = t->refs[r]->value_now;
    return n;
}

int chasm_live_tests(const chasm_machine *m, bool *out, int cap)
{
    int n = 0;
    for (int k = 0; k < m->n_aborts; k++)
        n = add_trans_tests(&m->aborts[k], n, out, cap);
    for (int d = 0; d < m->path_len; d++)
        for (int k = 0; k < m->path[d]->n_trans; k++)
            n = add_trans_tests(&m->path[d]->trans[k], n, out, cap);
    return n;
}

double chasm_var_number(const chasm_machine *m, int id)
{
    if (id < 0 || id >= m->n_vars) return NAN;
    const cm_var *v = &m->vars[id];
    if (!v->has_value) return NAN;
    switch (v->type) {
    case CHASM_DOUBLE: return v->d;
    case CHASM_INT: return (double)v->i;
    case CHASM_BOOL: return v->b ? 1.0 : 0.0;
    default: return NAN;
    }
}
