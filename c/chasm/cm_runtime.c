/* The cyclic step: actions by time model, tests, then at most one transition
 * checked along the active path from the root down. Works on the active path
 * only; no allocation, no lookups by name, no clock. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "chasm/cm_machine.h"

void cm_log(chasm_machine *m, const char *path, const char *fmt, ...)
{
    if (!m->opt.log) return;
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    m->opt.log(m->opt.log_user, m->now, path, buf);
}

double cm_age_s(const chasm_machine *m, int64_t stamp, int64_t now)
{
    if (stamp == CM_NEVER) return INFINITY;
    int64_t tol = m->opt.future_tolerance_us > 0 ? m->opt.future_tolerance_us : CHASM_FUTURE_TOLERANCE_US;
    if (stamp > cm_add_us(now, tol)) return INFINITY;
    int64_t d = cm_span_us(now, stamp);
    return d <= 0 ? 0.0 : (double)d * 1e-6;
}

static void ctx_init(cm_ext *x, chasm_machine *m, cm_binding *b, const cm_state *s, int64_t now, int64_t last)
{
    x->c.api = &cm_host_api;
    x->c.now_us = now;
    x->c.dt_s = last == CM_NEVER ? 0.0 : (double)cm_span_us(now, last) * 1e-6;
    x->c.time_in_state_s = (double)cm_span_us(now, s->entered_us) * 1e-6;
    x->c.state_path = s->path;
    x->c.engine = x;
    x->m = m;
    x->b = b;
}

static void mark_failed(cm_state *s)
{
    s->self_failed = true;
    for (; s; s = s->parent) s->failed = true;
}

static void write_value(cm_var *v, const cm_slot *val, int64_t now)
{
    switch (v->type) {
    case CHASM_DOUBLE: v->d = val->d; break;
    case CHASM_INT: v->i = val->i; v->d = (double)val->i; break;
    case CHASM_BOOL: v->b = val->b; v->d = val->b; break;
    case CHASM_STRING: snprintf(v->s, v->s_cap, "%s", val->s); break;
    case CHASM_MESSAGES: return;   /* `set` does not apply to a stream */
    }
    v->updated_us = now;
    v->has_value = true;
}

static void run_action(chasm_machine *m, cm_action *a, int64_t now)
{
    cm_state *s = a->state;
    if (a->kind == ACT_SET) {
        write_value(a->var, &a->value, now);
        a->last_run = now;
        return;
    }
    if (!a->started) return;
    cm_binding *b = a->cur;
    cm_ext x;
    ctx_init(&x, m, b, s, now, a->last_run);
    chasm_status_code r = b->beh->step(&x.c, b->inst);
    a->last_run = now;
    if (r == CHASM_FAILED) mark_failed(s);
    else if (r == CHASM_DONE && (a->tm == TM_CYCLE || a->tm == TM_EVERY)) s->done = true;
}

static void enter_state(chasm_machine *m, cm_state *s, int64_t now)
{
    s->entered_us = now;
    s->done = s->failed = s->self_failed = false;
    if (s->parent) s->parent->history_child = s;
    m->path[s->depth] = s;
    m->path_len = s->depth + 1;
    for (int i = 0; i < s->n_tests; i++) {
        cm_test *t = &s->tests[i];
        t->true_since = CM_NEVER;
        t->value_now = false;
        cm_binding_adopt_pending(m, &t->cur, &t->pending);
    }
    for (int i = 0; i < s->n_actions; i++) {
        cm_action *a = &s->actions[i];
        a->next_due = now;
        a->fired = false;
        a->last_run = CM_NEVER;
        if (a->kind == ACT_PLUGIN) {
            cm_binding_adopt_pending(m, &a->cur, &a->pending);
            cm_binding *b = a->cur;
            if (b->inst_size) memset(b->inst, 0, b->inst_size);
            /* an action entered now takes the messages that are new this cycle
             * on; what came before its state was entered is not its business */
            for (int k = 0; k < b->n_slots; k++)
                if (b->slots[k].var && b->slots[k].var->stream) b->slots[k].next_msg = b->slots[k].var->stream->cycle_first;
            a->started = true;
            if (b->beh->start) {
                cm_ext x;
                ctx_init(&x, m, b, s, now, CM_NEVER);
                if (b->beh->start(&x.c, b->inst)) {
                    mark_failed(s);
                    a->started = false;
                }
            }
        }
        if (a->tm == TM_ENTRY) run_action(m, a, now);
    }
}

static void exit_state(chasm_machine *m, cm_state *s, int64_t now)
{
    for (int i = 0; i < s->n_actions; i++) {
        cm_action *a = &s->actions[i];
        if (a->tm == TM_EXIT) run_action(m, a, now);
        if (a->kind != ACT_PLUGIN) continue;
        if (a->started && a->cur->beh->stop) {
            cm_ext x;
            ctx_init(&x, m, a->cur, s, now, a->last_run);
            a->cur->beh->stop(&x.c, a->cur->inst);
        }
        a->started = false;
        /* the old code is no longer in use: switch now so it can be unloaded */
        cm_binding_adopt_pending(m, &a->cur, &a->pending);
    }
    for (int i = 0; i < s->n_tests; i++) cm_binding_adopt_pending(m, &s->tests[i].cur, &s->tests[i].pending);
}

static bool on_path(const chasm_machine *m, const cm_state *s)
{
    return s->depth < m->path_len && m->path[s->depth] == s;
}

static void record(chasm_machine *m, const cm_state *from, const cm_trans *t, const char *cond, int64_t now)
{
    m->last_us = now;
    m->last_from = from;
    m->last_to = m->path_len ? m->path[m->path_len - 1] : NULL;
    m->last_cond = cond;
    m->last_trans = t;
    for (int i = 0; t && i < t->n_refs; i++) m->last_vals[i] = t->refs[i]->value_now;
}

/* Exit innermost-first up to the least common ancestor, enter outermost-first
 * down to the target, then down to a leaf by default child or history. */
static void go(chasm_machine *m, cm_state *target, cm_history hist, const cm_trans *t, const char *cond, int64_t now)
{
    const cm_state *from = m->path_len ? m->path[m->path_len - 1] : NULL;
    cm_state *lca = NULL;
    if (on_path(m, target)) lca = target->parent;
    else
        for (cm_state *a = target->parent; a; a = a->parent)
            if (on_path(m, a)) {
                lca = a;
                break;
            }
    int stop = lca ? lca->depth + 1 : 0;
    for (int d = m->path_len - 1; d >= stop; d--) exit_state(m, m->path[d], now);
    m->path_len = stop;
    cm_state *chain[CHASM_STATUS_MAX_DEPTH];
    int n = 0;
    for (cm_state *a = target; a != lca; a = a->parent) chain[n++] = a;
    while (n) enter_state(m, chain[--n], now);
    cm_state *cur = target;
    while (cur->first_child) {
        cm_state *next = hist != HIST_NONE && cur->history_child ? cur->history_child : cur->default_child;
        if (hist == HIST_SHALLOW) hist = HIST_NONE;
        enter_state(m, next, now);
        cur = next;
    }
    /* A failure is handled once the failing state is left: ancestors that stay
     * active keep `failed` only for their own actions or a still-active child. */
    for (int d = m->path_len - 1; d >= 0; d--)
        m->path[d]->failed = m->path[d]->self_failed || (d + 1 < m->path_len && m->path[d + 1]->failed);
    record(m, from, t, cond, now);
}

static void finish(chasm_machine *m, chasm_run_state how, const char *cond, int64_t now)
{
    const cm_state *from = m->path_len ? m->path[m->path_len - 1] : NULL;
    for (int d = m->path_len - 1; d >= 0; d--) exit_state(m, m->path[d], now);
    m->run = how;
    record(m, from, NULL, cond, now);
    m->last_to = NULL;
}

void cm_stop_all(chasm_machine *m) { finish(m, CHASM_RUN_DONE, "stopped", m->now); }

static bool cmp(double a, cm_cmp op, double b)
{
    switch (op) {
    case OP_LT: return a < b;
    case OP_LE: return a <= b;
    case OP_GT: return a > b;
    case OP_GE: return a >= b;
    case OP_EQ: return a == b;
    case OP_NE: return a != b;
    }
    return false;
}

static bool eval_raw(chasm_machine *m, cm_test *t, int64_t now)
{
    const cm_var *v = t->var;
    switch (t->kind) {
    case CR_ELAPSED: {
        int64_t since = t->state ? t->state->entered_us : m->start_us;
        return cmp((double)cm_span_us(now, since) * 1e-6, t->op, t->value);
    }
    case CR_AGE: return cmp(cm_age_s(m, v->updated_us, now), t->op, t->value);
    case CR_HANDLER: {
        cm_ext x;
        const cm_state *s = t->state ? t->state : m->path[0];
        ctx_init(&x, m, t->cur, s, now, CM_NEVER);
        return t->cur->test->evaluate(&x.c) != 0;
    }
    case CR_BOOLVAR: return v->has_value && v->b;
    default: break;
    }
    if (!v->has_value) return false;
    if (v->type == CHASM_BOOL) return (t->op == OP_EQ) == (v->b == (t->value != 0));
    if (v->type == CHASM_STRING) return (t->op == OP_EQ) == (strcmp(v->s, t->sval) == 0);
    double diff = v->d - t->value;
    if (t->angle) diff = remainder(diff, 6.283185307179586);
    double tol = t->tol;
    if (t->kind == CR_WITHIN) return fabs(diff) <= tol;
    switch (t->op) {
    case OP_LT: return diff < tol;
    case OP_LE: return diff <= tol;
    case OP_GT: return diff > -tol;
    case OP_GE: return diff >= -tol;
    case OP_EQ: return fabs(diff) <= tol;
    case OP_NE: return fabs(diff) > tol;
    }
    return false;
}

static void eval_test(chasm_machine *m, cm_test *t, int64_t now)
{
    if (eval_raw(m, t, now)) {
        if (t->true_since == CM_NEVER) t->true_since = now;
        t->value_now = cm_span_us(now, t->true_since) >= t->hold_us;
    } else {
        t->true_since = CM_NEVER;
        t->value_now = false;
    }
}

static bool eval_cond(const chasm_machine *m, const cm_trans *t, int64_t now)
{
    bool st[256];
    int sp = 0;
    for (int i = 0; i < t->n_code; i++) {
        const cm_cop *c = &t->code[i];
        switch ((cm_op)c->op) {
        case CO_TEST: st[sp++] = c->test->value_now; break;
        case CO_DONE: st[sp++] = m->states[c->arg].done; break;
        case CO_FAILED: st[sp++] = m->states[c->arg].failed; break;
        case CO_ELAPSED: {
            int64_t since = c->arg < 0 ? m->start_us : m->states[c->arg].entered_us;
            st[sp++] = cmp((double)cm_span_us(now, since), (cm_cmp)c->cmp, (double)c->t_us);
            break;
        }
        case CO_TRUE: st[sp++] = true; break;
        case CO_FALSE: st[sp++] = false; break;
        case CO_AND: sp--; st[sp - 1] = st[sp - 1] && st[sp]; break;
        case CO_OR: sp--; st[sp - 1] = st[sp - 1] || st[sp]; break;
        case CO_NOT: st[sp - 1] = !st[sp - 1]; break;
        }
    }
    return sp == 1 && st[0];
}

int chasm_start(chasm_machine *m, int64_t now)
{
    if (m->run != CHASM_RUN_LOADED) return -1;
    m->run = CHASM_RUN_RUNNING;
    m->now = now;
    m->start_us = now;
    m->path_len = 0;
    cm_streams_begin_cycle(m);
    go(m, m->initial, HIST_NONE, NULL, "start", now);
    cm_streams_commit(m, now);
    return 0;
}

static chasm_run_state step(chasm_machine *m, int64_t now);

/* Posts of the cycle (and of exit and entry actions) enter their streams
 * when it ends, however it ended. */
chasm_run_state chasm_step(chasm_machine *m, int64_t now)
{
    if (m->run != CHASM_RUN_RUNNING) return m->run;
    cm_streams_begin_cycle(m);
    chasm_run_state r = step(m, now);
    cm_streams_commit(m, now);
    return r;
}

static chasm_run_state step(chasm_machine *m, int64_t now)
{
    m->now = now;
    m->cycle++;
    const int len = m->path_len;
    for (int d = 0; d < len; d++) {
        cm_state *s = m->path[d];
        for (int i = 0; i < s->n_actions; i++) {
            cm_action *a = &s->actions[i];
            switch (a->tm) {
            case TM_CYCLE: run_action(m, a, now); break;
            case TM_EVERY:
                if (now >= a->next_due) {
                    run_action(m, a, now);
                    a->next_due = cm_add_us(a->next_due, a->period_us);
                    if (a->next_due <= now) a->next_due = cm_add_us(now, a->period_us); /* late: skip, never burst */
                }
                break;
            case TM_AFTER:
                if (!a->fired && cm_span_us(now, s->entered_us) >= a->period_us) {
                    a->fired = true;
                    run_action(m, a, now);
                }
                break;
            default: break;
            }
        }
    }
    for (int i = 0; i < m->n_globals; i++) eval_test(m, &m->globals[i], now);
    for (int d = 0; d < len; d++) {
        cm_state *s = m->path[d];
        for (int i = 0; i < s->n_tests; i++) eval_test(m, &s->tests[i], now);
    }
    /* completion bubbles up: a state that completes with no `next` completes its
     * parent, unless one of its own `when` tests `done` (then that handles it) */
    for (int d = len - 1; d >= 1; d--) {
        cm_state *s = m->path[d];
        if (s->done && !s->next && !s->next_done && !s->handles_done) s->parent->done = true;
    }
    for (int i = 0; i < m->n_aborts; i++) {
        cm_trans *t = &m->aborts[i];
        if (!on_path(m, t->target) && eval_cond(m, t, now)) {
            go(m, t->target, t->history, t, t->text, now);
            return m->run;
        }
    }
    for (int d = 0; d < len; d++) {
        cm_state *s = m->path[d];
        for (int i = 0; i < s->n_trans; i++) {
            cm_trans *t = &s->trans[i];
            if (eval_cond(m, t, now)) {
                go(m, t->target, t->history, t, t->text, now);
                return m->run;
            }
        }
        if (s->done && (s->next || s->next_done || !s->parent)) {
            if (s->next) go(m, s->next, HIST_NONE, NULL, "completed", now);
            else finish(m, CHASM_RUN_DONE, "completed", now);
            return m->run;
        }
    }
    for (int d = len - 1; d >= 0; d--)
        if (m->path[d]->failed) {
            snprintf(m->abort_text, sizeof m->abort_text, "failure in '%s' not caught", m->path[len - 1]->path);
            finish(m, CHASM_RUN_FAILED, m->abort_text, now);
            break;
        }
    return m->run;
}

void chasm_abort(chasm_machine *m, int64_t now, const char *reason)
{
    if (m->run != CHASM_RUN_RUNNING && m->run != CHASM_RUN_PAUSED) return;
    m->now = now;
    snprintf(m->abort_text, sizeof m->abort_text, "operator abort%s%s", reason && *reason ? ": " : "",
             reason ? reason : "");
    m->run = CHASM_RUN_RUNNING;
    if (m->n_aborts) {
        if (!on_path(m, m->aborts[0].target)) go(m, m->aborts[0].target, HIST_NONE, NULL, m->abort_text, now);
    } else finish(m, CHASM_RUN_ABORTED, m->abort_text, now);
    cm_streams_commit(m, now);
}

void chasm_pause(chasm_machine *m, bool paused)
{
    if (paused && m->run == CHASM_RUN_RUNNING) m->run = CHASM_RUN_PAUSED;
    else if (!paused && m->run == CHASM_RUN_PAUSED) m->run = CHASM_RUN_RUNNING;
}

chasm_run_state chasm_run_state_of(const chasm_machine *m) { return m->run; }

const char *chasm_run_state_name(chasm_run_state s)
{
    static const char *n[] = {"loaded", "running", "paused", "done", "aborted", "failed"};
    return (unsigned)s < 6 ? n[s] : "?";
}
