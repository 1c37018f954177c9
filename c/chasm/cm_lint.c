/* Deeper checks of a loaded plan than loading makes (chasm_lint in
 * chasm_structure.h, `chasm check`): what loads but cannot work as written.
 *
 * - unreachable: a state no start, next, transition or abort can enter;
 * - never-fires: a transition whose condition is `false`, whose tests joined
 *   by `and` ask one variable for ranges that do not meet, or that an earlier
 *   transition of its own state or of an enclosing state, always true,
 *   pre-empts (outer states and earlier transitions are checked first);
 * - no-way-out: a leaf state that, with every state around it, has no
 *   transition, no `next` and no action that can complete it: the plan stays
 *   there forever unless an abort fires;
 * - unwritten-output: an output variable no action writes;
 * - shadowed-abort: an abort whose target has child states: while one of
 *   them is active the target is on the active path, and an abort whose
 *   target is active is skipped, so the rule does not protect them. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "chasm/chasm_structure.h"
#include "chasm/cm_machine.h"

typedef struct {
    const chasm_machine *m;
    chasm_finding_fn fn;
    void *user;
    int n;
} lint;

__attribute__((format(printf, 4, 5))) static void report(lint *l, cm_loc loc, const char *kind, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    l->fn(l->user, (chasm_where){loc.file ? loc.file : "", loc.line, loc.col}, kind, msg);
    l->n++;
}

/* ------------------------------------------------------------ reachability */
static void enter(const chasm_machine *m, const cm_state *s, bool *in, bool *changed)
{
    for (const cm_state *a = s; a; a = a->parent)
        if (!in[a->index]) in[a->index] = *changed = true;
    for (const cm_state *c = s->default_child; c; c = c->default_child)
        if (!in[c->index]) in[c->index] = *changed = true;
    (void)m;
}

static void unreachable(lint *l)
{
    const chasm_machine *m = l->m;
    if (!m->initial) return;
    bool *in = calloc((size_t)m->n_states + 1, sizeof *in);
    if (!in) return;
    bool changed = false;
    enter(m, m->initial, in, &changed);
    for (int k = 0; k < m->n_aborts; k++) enter(m, m->aborts[k].target, in, &changed);
    for (changed = true; changed;) {
        changed = false;
        for (int i = 0; i < m->n_states; i++) {
            const cm_state *s = &m->states[i];
            if (!in[i]) continue;
            if (s->next) enter(m, s->next, in, &changed);
            for (int k = 0; k < s->n_trans; k++) enter(m, s->trans[k].target, in, &changed);
        }
    }
    for (int i = 0; i < m->n_states; i++)
        if (!in[i] && (!m->states[i].parent || in[m->states[i].parent->index]))
            report(l, m->states[i].loc, "unreachable", "state '%s' can never be entered: no start, next, transition or abort leads to it",
                   m->states[i].path);
    free(in);
}

/* ------------------------------------------------------------ conditions */
typedef struct {
    const cm_var *var;
    double lo, hi;
    bool lo_open, hi_open;
} range;

/* The values of its variable a comparison test accepts; false if not a plain range. */
static bool test_range(const cm_test *t, range *r)
{
    if (!t->var || t->angle || t->var->type == CHASM_STRING || t->var->type == CHASM_MESSAGES) return false;
    *r = (range){t->var, -INFINITY, INFINITY, false, false};
    if (t->kind == CR_WITHIN) {
        if (!t->has_tol) return false;
        r->lo = t->value - t->tol;
        r->hi = t->value + t->tol;
        return true;
    }
    if (t->kind != CR_CMP) return false;
    switch (t->op) {
    case OP_LT: r->hi = t->value; r->hi_open = true; return true;
    case OP_LE: r->hi = t->value; return true;
    case OP_GT: r->lo = t->value; r->lo_open = true; return true;
    case OP_GE: r->lo = t->value; return true;
    case OP_EQ: r->lo = r->hi = t->value; return true;
    default: return false;
    }
}

/* Two tests joined by `and` that no value of their variable satisfies. */
static bool ranges_meet(const range *a, const range *b)
{
    double lo = fmax(a->lo, b->lo), hi = fmin(a->hi, b->hi);
    bool lo_open = (a->lo == lo && a->lo_open) || (b->lo == lo && b->lo_open);
    bool hi_open = (a->hi == hi && a->hi_open) || (b->hi == hi && b->hi_open);
    return lo < hi || (lo == hi && !lo_open && !hi_open);
}

/* A condition of tests and other terms joined by `and` only. */
static bool all_and(const cm_trans *t)
{
    for (int i = 0; i < t->n_code; i++)
        if (t->code[i].op == CO_OR || t->code[i].op == CO_NOT) return false;
    return true;
}

static bool is_constant(const cm_trans *t, int op) { return t->n_code == 1 && t->code[0].op == op; }

static void contradicted(lint *l, const cm_trans *t)
{
    if (is_constant(t, CO_FALSE)) {
        report(l, t->loc, "never-fires", "transition '%s' can never fire: its condition is false", t->text);
        return;
    }
    if (!all_and(t)) return;
    for (int i = 0; i < t->n_code; i++) {
        range a;
        if (t->code[i].op != CO_TEST || !test_range(t->code[i].test, &a)) continue;
        for (int j = i + 1; j < t->n_code; j++) {
            range b;
            if (t->code[j].op != CO_TEST || !test_range(t->code[j].test, &b) || b.var != a.var) continue;
            if (!ranges_meet(&a, &b)) {
                report(l, t->loc, "never-fires",
                       "transition '%s' can never fire: tests '%s' and '%s' ask %s for values that do not meet", t->text,
                       t->code[i].test->name, t->code[j].test->name, a.var->name);
                return;
            }
        }
    }
}

/* Transitions after one that is always true, in its state or below it. */
static void preempted(lint *l)
{
    const chasm_machine *m = l->m;
    for (int i = 0; i < m->n_states; i++) {
        const cm_state *s = &m->states[i];
        for (int k = 0; k < s->n_trans; k++) {
            const cm_trans *t = &s->trans[k];
            for (const cm_state *a = s; a; a = a->parent)
                for (int j = 0; j < a->n_trans && !(a == s && j >= k); j++)
                    if (is_constant(&a->trans[j], CO_TRUE)) {
                        report(l, t->loc, "never-fires", "transition '%s' can never fire: '%s' of state '%s' (%s:%d) is always true and is checked first",
                               t->text, a->trans[j].text, a->path, a->trans[j].loc.file, a->trans[j].loc.line);
                        goto next;
                    }
        next:;
        }
    }
}

/* ------------------------------------------------------------ no way out */
static bool can_complete(const cm_state *s)
{
    for (int k = 0; k < s->n_actions; k++)
        if (s->actions[k].kind == ACT_PLUGIN && (s->actions[k].tm == TM_CYCLE || s->actions[k].tm == TM_EVERY)) return true;
    return false;
}

static void no_way_out(lint *l)
{
    const chasm_machine *m = l->m;
    for (int i = 0; i < m->n_states; i++) {
        const cm_state *s = &m->states[i];
        if (s->first_child) continue;
        bool out = false;
        for (const cm_state *a = s; a && !out; a = a->parent)
            out = a->n_trans || a->next || a->next_done || can_complete(a);
        if (!out)
            report(l, s->loc, "no-way-out",
                   "state '%s' has no way out and no time limit: no transition, next or completing action in it or around it",
                   s->path);
    }
}

/* ------------------------------------------------------------ outputs */
static bool writes(const cm_action *a, const cm_var *v)
{
    if (a->kind == ACT_SET) return a->var == v;
    const cm_binding *b = a->cur;
    for (int k = 0; b && k < b->n_slots; k++)
        if (b->specs[k].kind == CHASM_WRITES && b->slots[k].var == v) return true;
    return false;
}

static void unwritten_outputs(lint *l)
{
    const chasm_machine *m = l->m;
    for (int v = 0; v < m->n_vars; v++) {
        const cm_var *var = &m->vars[v];
        if (var->kind != CHASM_VAR_OUTPUT) continue;
        bool w = false;
        for (int i = 0; i < m->n_states && !w; i++)
            for (int k = 0; k < m->states[i].n_actions && !w; k++)
                w = writes(&m->states[i].actions[k], var);
        if (!w) report(l, var->loc, "unwritten-output", "output '%s' is never written: no action sets it", var->name);
    }
}

/* ------------------------------------------------------------ aborts */
static void shadowed_aborts(lint *l)
{
    const chasm_machine *m = l->m;
    for (int k = 0; k < m->n_aborts; k++) {
        const cm_trans *t = &m->aborts[k];
        if (t->target && t->target->first_child)
            report(l, t->loc, "shadowed-abort",
                   "abort '%s' goes to '%s', which has child states: while '%s' (or any state in it) is active the "
                   "abort is skipped",
                   t->text, t->target->path, t->target->first_child->path);
    }
}

int chasm_lint(const chasm_machine *m, chasm_finding_fn fn, void *user)
{
    lint l = {m, fn, user, 0};
    unreachable(&l);
    for (int k = 0; k < m->n_aborts; k++) contradicted(&l, &m->aborts[k]);
    for (int i = 0; i < m->n_states; i++)
        for (int k = 0; k < m->states[i].n_trans; k++) contradicted(&l, &m->states[i].trans[k]);
    preempted(&l);
    no_way_out(&l);
    unwritten_outputs(&l);
    shadowed_aborts(&l);
    return l.n;
}
