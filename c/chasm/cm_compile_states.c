/* States: the forest, names, default child and default next; transitions and
 * their conditions compiled to postfix code over test indices. */
#include <stdio.h>
#include <string.h>

#include "chasm/cm_compile.h"

static int count(const cm_astate *s)
{
    int n = 0;
    for (; s; s = s->next) n += 1 + count(s->children);
    return n;
}

static void build(cm_cc *cc, const cm_astate *a, cm_state *parent, int *idx)
{
    cm_state *prev = NULL;
    for (; a; a = a->next) {
        cm_state *s = &cc->m->states[(*idx)++];
        s->index = (int)(s - cc->m->states);
        s->name = a->name;
        s->parent = parent;
        s->depth = parent ? parent->depth + 1 : 0;
        s->path = parent ? cm_sprintf(cc->a, "%s/%s", parent->path, a->name) : a->name;
        s->loc = a->loc;
        s->ast = a;
        s->entered_us = CM_NEVER;
        cm_state *dup = cm_map_put(&cc->path_map, s->path, s);
        if (dup) {
            if (parent)
                cm_error(cc->d, a->loc, "state '%s' is defined twice in state '%s' (first at %s:%d:%d)", a->name,
                         parent->name, dup->loc.file, dup->loc.line, dup->loc.col);
            else
                cm_error(cc->d, a->loc, "root state '%s' is defined twice (first at %s:%d:%d)", a->name,
                         dup->loc.file, dup->loc.line, dup->loc.col);
        }
        cm_state *other = cm_map_put(&cc->name_map, s->name, s);
        if (other && other != (cm_state *)&cc->ambiguous) {
            /* keep the key, mark it ambiguous: a bare name must then be qualified */
            for (size_t i = 0; i < cc->name_map.cap; i++)
                if (cc->name_map.keys[i] && !strcmp(cc->name_map.keys[i], s->name)) cc->name_map.vals[i] = &cc->ambiguous;
        }
        if (parent && !parent->first_child) parent->first_child = s;
        if (prev) prev->next_sibling = s;
        prev = s;
        build(cc, a->children, s, idx);
    }
}

static cm_state *resolve(cm_cc *cc, const char *ref, cm_loc loc, cm_state *from, const char *what)
{
    const char *key;
    if (strchr(ref, '/')) {
        cm_state *s = cm_map_get(&cc->path_map, ref);
        if (s) return s;
        cm_state *found = NULL;
        size_t L = strlen(ref);
        for (int i = 0; i < cc->m->n_states; i++) {
            const char *p = cc->m->states[i].path;
            size_t pl = strlen(p);
            if (pl > L && p[pl - L - 1] == '/' && !strcmp(p + pl - L, ref)) {
                if (found) {
                    cm_error(cc->d, loc, "%s '%s' is ambiguous: '%s' or '%s'", what, ref, found->path, p);
                    return NULL;
                }
                found = &cc->m->states[i];
            }
        }
        if (found) return found;
    } else {
        for (cm_state *s = from; s; s = s->parent) {
            key = cm_sprintf(cc->a, "%s/%s", s->path, ref);
            cm_state *t = cm_map_get(&cc->path_map, key);
            if (t) return t;
        }
        cm_state *t = cm_map_get(&cc->path_map, ref);
        if (t) return t;
        t = cm_map_get(&cc->name_map, ref);
        if (t == (cm_state *)&cc->ambiguous) {
            const char *a = NULL, *b = NULL;
            for (int i = 0; i < cc->m->n_states && !b; i++)
                if (!strcmp(cc->m->states[i].name, ref)) {
                    if (!a) a = cc->m->states[i].path;
                    else b = cc->m->states[i].path;
                }
            cm_error(cc->d, loc, "%s '%s' is ambiguous: write '%s' or '%s'", what, ref, a, b);
            return NULL;
        }
        if (t) return t;
    }
    cm_suggest s;
    const char *last = strrchr(ref, '/');
    cm_suggest_init(&s, last ? last + 1 : ref);
    for (int i = 0; i < cc->m->n_states; i++) cm_suggest_add(&s, cc->m->states[i].name);
    char h[96];
    cm_error(cc->d, loc, "unknown %s '%s'%s", what, ref, cm_suggest_hint(&s, h, sizeof h));
    return NULL;
}

void cm_compile_states(cm_cc *cc)
{
    chasm_machine *m = cc->m;
    m->n_states = count(cc->plan->roots);
    m->states = cm_alloc(cc->a, sizeof *m->states * (size_t)(m->n_states ? m->n_states : 1));
    int idx = 0;
    build(cc, cc->plan->roots, NULL, &idx);
    for (int i = 0; i < m->n_states; i++) {
        cm_state *s = &m->states[i];
        const cm_astate *a = s->ast;
        if (a->start) {
            if (!s->first_child) {
                cm_error(cc->d, a->start_loc, "state '%s' has no child states, so 'start %s' has nothing to start",
                         s->name, a->start);
            } else {
                const char *key;
                key = cm_sprintf(cc->a, "%s/%s", s->path, a->start);
                s->default_child = cm_map_get(&cc->path_map, key);
                if (!s->default_child) {
                    cm_suggest sg;
                    cm_suggest_init(&sg, a->start);
                    for (cm_state *c = s->first_child; c; c = c->next_sibling) cm_suggest_add(&sg, c->name);
                    char h[96];
                    cm_error(cc->d, a->start_loc, "'%s' is not a child of state '%s'%s", a->start, s->name,
                             cm_suggest_hint(&sg, h, sizeof h));
                }
            }
        }
        if (!s->default_child) s->default_child = s->first_child;
        if (a->next_state) s->next = resolve(cc, a->next_state, a->next_loc, s, "next state");
        s->next_done = a->next_is_done;
    }
    if (!m->n_states) {
        cm_error(cc->d, (cm_loc){cc->m->plan_name ? cc->m->plan_name : "plan", 0, 1, 1},
                 "the plan has no states (write `state NAME { ... }`)");
        return;
    }
    m->initial = &m->states[0];
    if (cc->plan->start) {
        cm_state *s = cm_map_get(&cc->path_map, cc->plan->start);
        if (!s) {
            cm_suggest sg;
            cm_suggest_init(&sg, cc->plan->start);
            for (cm_state *r = &m->states[0]; r; r = r->next_sibling) cm_suggest_add(&sg, r->name);
            char h[96];
            cm_error(cc->d, cc->plan->start_loc, "'start %s': there is no root state '%s'%s", cc->plan->start,
                     cc->plan->start, cm_suggest_hint(&sg, h, sizeof h));
        } else m->initial = s;
    }
}

/* ----------------------------------------------------------- transitions */

typedef struct {
    cm_cop *code;
    int n, cap, depth, max_depth;
    cm_test **refs;
    int n_refs;
} emitter;

static void emit(cm_cc *cc, emitter *e, cm_cop op, int push)
{
    if (e->n == e->cap) {
        int nc = e->cap ? e->cap * 2 : 8;
        cm_cop *c = cm_alloc(cc->a, sizeof *c * (size_t)nc);
        if (e->n) memcpy(c, e->code, sizeof *c * (size_t)e->n);
        e->code = c;
        e->cap = nc;
    }
    e->code[e->n++] = op;
    e->depth += push;
    if (e->depth > e->max_depth) e->max_depth = e->depth;
}

static cm_test *find_test(cm_cc *cc, const char *name, cm_state *owner)
{
    const char *key;
    for (cm_state *s = owner; s; s = s->parent) {
        key = cm_sprintf(cc->a, "%s:%s", s->path, name);
        cm_test *t = cm_map_get(&cc->test_map, key);
        if (t) return t;
    }
    key = cm_sprintf(cc->a, ":%s", name);
    return cm_map_get(&cc->test_map, key);
}

static int compile_expr(cm_cc *cc, emitter *e, const cm_aexpr *x, cm_state *owner)
{
    int ok = 0;
    switch (x->kind) {
    case E_AND:
    case E_OR:
        ok = compile_expr(cc, e, x->a, owner);
        ok |= compile_expr(cc, e, x->b, owner);
        emit(cc, e, (cm_cop){(uint8_t)(x->kind == E_AND ? CO_AND : CO_OR), 0, 0, 0, NULL}, -1);
        return ok;
    case E_NOT:
        ok = compile_expr(cc, e, x->a, owner);
        emit(cc, e, (cm_cop){CO_NOT, 0, 0, 0, NULL}, 0);
        return ok;
    case E_TRUE: emit(cc, e, (cm_cop){CO_TRUE, 0, 0, 0, NULL}, 1); return 0;
    case E_FALSE: emit(cc, e, (cm_cop){CO_FALSE, 0, 0, 0, NULL}, 1); return 0;
    case E_DONE:
    case E_FAILED:
        if (!owner) {
            cm_error(cc->d, x->loc, "'%s' refers to a state: use it in a state's `when`, not in `abort when`",
                     x->kind == E_DONE ? "done" : "failed");
            return -1;
        }
        if (x->kind == E_DONE) owner->handles_done = true;
        emit(cc, e, (cm_cop){(uint8_t)(x->kind == E_DONE ? CO_DONE : CO_FAILED), 0, owner->index, 0, NULL}, 1);
        return 0;
    case E_ELAPSED: {
        int64_t us = 0;
        if (cm_duration(cc, &x->val, "'elapsed'", &us)) return -1;
        emit(cc, e, (cm_cop){CO_ELAPSED, (uint8_t)x->op, owner ? owner->index : -1, us, NULL}, 1);
        return 0;
    }
    case E_TEST: {
        cm_test *t = find_test(cc, x->name, owner);
        if (!t) {
            cm_suggest sg;
            cm_suggest_init(&sg, x->name);
            for (cm_state *s = owner; s; s = s->parent)
                for (int i = 0; i < s->n_tests; i++) cm_suggest_add(&sg, s->tests[i].name);
            for (int i = 0; i < cc->m->n_globals; i++) cm_suggest_add(&sg, cc->m->globals[i].name);
            char h[96];
            const char *hint = cm_suggest_hint(&sg, h, sizeof h);
            cm_error(cc->d, x->loc, "unknown test '%s'%s", x->name,
                     *hint ? hint : (owner ? " (tests of this state, its parents and the top level are visible here)"
                                           : " (only top-level tests are visible in `abort when`)"));
            return -1;
        }
        if (t == (cm_test *)&cc->ambiguous) return -1;
        int known = 0;
        for (int i = 0; i < e->n_refs; i++) known |= e->refs[i] == t;
        if (!known && e->n_refs < CHASM_STATUS_MAX_TESTS) e->refs[e->n_refs++] = t;
        emit(cc, e, (cm_cop){CO_TEST, 0, 0, 0, t}, 1);
        return 0;
    }
    }
    return -1;
}

static void compile_one(cm_cc *cc, const cm_atrans *a, cm_state *owner, cm_trans *t)
{
    t->owner = owner;
    t->loc = a->loc;
    t->text = a->text;
    t->history = a->history;
    emitter e = {0};
    e.refs = cm_alloc(cc->a, sizeof *e.refs * CHASM_STATUS_MAX_TESTS);
    compile_expr(cc, &e, a->cond, owner);
    if (e.max_depth > 200) cm_error(cc->d, a->loc, "condition is too complex (split it into several tests)");
    t->code = e.code;
    t->n_code = e.n;
    t->refs = e.refs;
    t->n_refs = e.n_refs;
    t->target = resolve(cc, a->target, a->target_loc, owner, "target state");
    if (t->target && a->history != HIST_NONE && !t->target->first_child)
        cm_error(cc->d, a->target_loc, "'resume %s' needs a state with children to remember (it has none)",
                 t->target->name);
}

void cm_compile_transitions(cm_cc *cc)
{
    chasm_machine *m = cc->m;
    for (int i = 0; i < m->n_states; i++) {
        cm_state *s = &m->states[i];
        int n = 0;
        for (cm_atrans *a = s->ast->trans; a; a = a->next) n++;
        s->trans = cm_alloc(cc->a, sizeof *s->trans * (size_t)(n ? n : 1));
        for (cm_atrans *a = s->ast->trans; a; a = a->next) compile_one(cc, a, s, &s->trans[s->n_trans++]);
    }
    int n = 0;
    for (cm_atrans *a = cc->plan->aborts; a; a = a->next) n++;
    m->aborts = cm_alloc(cc->a, sizeof *m->aborts * (size_t)(n ? n : 1));
    for (cm_atrans *a = cc->plan->aborts; a; a = a->next) compile_one(cc, a, NULL, &m->aborts[m->n_aborts++]);
}
