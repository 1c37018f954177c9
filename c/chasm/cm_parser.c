#include "chasm/cm_parser.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "chasm/cm_lexer.h"

/* Reserved words cannot name anything. Other words of the language (entry,
 * exit, cycle, every, after, for, within, of, tolerance, age, deep) are only
 * special where they are expected, so states may be called `after` or `deep`. */
static const char *keywords[] = {
    "include", "param", "use", "input", "output", "var", "test", "abort", "when", "start", "next",
    "state", "do", "set", "and", "or", "not", "true", "false", "resume", "done", "failed", "elapsed", NULL};

/* Words that may follow a number and so are never read as its unit. */
static const char *after_number[] = {"of", "for", "tolerance", "on", "every", "after", "and", "or", "at", NULL};

static int stops_unit(const char *s)
{
    for (int i = 0; after_number[i]; i++)
        if (!strcmp(s, after_number[i])) return 1;
    return 0;
}

int cm_is_keyword(const char *s)
{
    for (int i = 0; keywords[i]; i++)
        if (!strcmp(s, keywords[i])) return 1;
    return 0;
}

typedef struct {
    cm_parse_ctx *ctx;
    cm_token *t;
    size_t pos, n;
    const char *file;
    const char *dir;
    int order;
    int failed;     /* current statement had an error: skip to its end */
} P;

static cm_token *cur(P *p) { return &p->t[p->pos]; }
static cm_token *peek(P *p, int k)
{
    size_t i = p->pos + (size_t)k;
    return &p->t[i < p->n ? i : p->n - 1];
}
static cm_loc loc_of(P *p, cm_token *t) { return (cm_loc){p->file, p->order, t->line, t->col}; }
static void adv(P *p)
{
    if (p->pos + 1 < p->n) p->pos++;
}
static int is_kw(cm_token *t, const char *kw) { return t->type == T_IDENT && !strcmp(t->text, kw); }

static void describe(cm_token *t, char *buf, size_t n)
{
    if (t->type == T_IDENT) snprintf(buf, n, "'%s'", t->text);
    else if (t->type == T_NUMBER) snprintf(buf, n, "number '%.*s'", t->len, t->start);
    else snprintf(buf, n, "%s", cm_tok_name(t->type));
}

static void err_expected(P *p, const char *what)
{
    if (p->failed) return;
    char b[128];
    describe(cur(p), b, sizeof b);
    cm_error(p->ctx->diag, loc_of(p, cur(p)), "expected %s, found %s", what, b);
    p->failed = 1;
}

static int expect(P *p, cm_tok_type ty, const char *what)
{
    if (cur(p)->type == ty) {
        adv(p);
        return 1;
    }
    err_expected(p, what);
    return 0;
}

/* A user-chosen name: an identifier that is not a reserved word. */
static char *name(P *p, const char *what, cm_loc *loc)
{
    cm_token *t = cur(p);
    if (loc) *loc = loc_of(p, t);
    if (t->type == T_IDENT && !cm_is_keyword(t->text)) {
        adv(p);
        return t->text;
    }
    if (t->type == T_IDENT && !p->failed) {
        cm_error(p->ctx->diag, loc_of(p, t), "'%s' is a reserved word and cannot be used as %s", t->text, what);
        p->failed = 1;
        return NULL;
    }
    err_expected(p, what);
    return NULL;
}

/* Skips the rest of a statement, including any block it opened. */
static void sync(P *p)
{
    int depth = 0;
    for (;;) {
        cm_token *t = cur(p);
        if (t->type == T_EOF) break;
        if (t->type == T_LBRACE) depth++;
        if (t->type == T_RBRACE) {
            if (depth == 0) break;
            depth--;
            if (depth == 0) {
                adv(p);
                break;
            }
        }
        if (t->type == T_NEWLINE && depth == 0) {
            adv(p);
            break;
        }
        adv(p);
    }
    p->failed = 0;
}

static void end_statement(P *p)
{
    if (!p->failed) {
        cm_token *t = cur(p);
        if (t->type == T_NEWLINE) adv(p);
        else if (t->type != T_EOF && t->type != T_RBRACE) err_expected(p, "end of line");
    }
    if (p->failed) sync(p);
}

/* unit := IDENT [ '/' IDENT ], only when an identifier follows a number. */
static void unit_after_number(P *p, cm_aval *v)
{
    cm_token *t = cur(p);
    if (t->type != T_IDENT || cm_is_keyword(t->text) || stops_unit(t->text) || t->line != peek(p, -1)->line) return;
    char buf[64];
    snprintf(buf, sizeof buf, "%s", t->text);
    cm_loc l = loc_of(p, t);
    adv(p);
    if (cur(p)->type == T_SLASH && peek(p, 1)->type == T_IDENT) {
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "/%s", peek(p, 1)->text);
        adv(p);
        adv(p);
    }
    v->unit = cm_unit_find(buf);
    if (!v->unit && !p->failed) {
        cm_suggest s;
        cm_suggest_init(&s, buf);
        for (int i = 1; cm_unit_name_at(i); i++) cm_suggest_add(&s, cm_unit_name_at(i));
        char h[96];
        cm_error(p->ctx->diag, l, "unknown unit '%s'%s", buf, cm_suggest_hint(&s, h, sizeof h));
        p->failed = 1;
    }
}

static cm_aval value(P *p, const char *what)
{
    cm_aval v = {0};
    cm_token *t = cur(p);
    v.loc = loc_of(p, t);
    int neg = 0;
    if (t->type == T_MINUS && peek(p, 1)->type == T_NUMBER) {
        neg = 1;
        adv(p);
        t = cur(p);
    }
    switch (t->type) {
    case T_NUMBER:
        v.kind = V_NUMBER;
        v.num = neg ? -t->num : t->num;
        v.is_int = !memchr(t->start, '.', (size_t)t->len) && !memchr(t->start, 'e', (size_t)t->len) &&
                   !memchr(t->start, 'E', (size_t)t->len);
        adv(p);
        unit_after_number(p, &v);
        return v;
    case T_STRING: v.kind = V_STRING; v.str = t->text; adv(p); return v;
    case T_PARAM: v.kind = V_PARAM; v.str = t->text; adv(p); return v;
    case T_IDENT:
        if (!strcmp(t->text, "true") || !strcmp(t->text, "false")) {
            v.kind = V_BOOL;
            v.b = t->text[0] == 't';
            adv(p);
            return v;
        }
        if (!cm_is_keyword(t->text)) {
            v.kind = V_NAME;
            v.str = t->text;
            adv(p);
            return v;
        }
        /* fallthrough */
    default: err_expected(p, what); return v;
    }
}

static int cmp_op(P *p, cm_cmp *op)
{
    switch (cur(p)->type) {
    case T_LT: *op = OP_LT; break;
    case T_LE: *op = OP_LE; break;
    case T_GT: *op = OP_GT; break;
    case T_GE: *op = OP_GE; break;
    case T_EQ: *op = OP_EQ; break;
    case T_NE: *op = OP_NE; break;
    case T_ASSIGN:
        if (!p->failed) {
            cm_error(p->ctx->diag, loc_of(p, cur(p)), "'=' assigns; to compare write '=='");
            p->failed = 1;
        }
        return 0;
    default: err_expected(p, "a comparison (<, <=, >, >=, ==, !=)"); return 0;
    }
    adv(p);
    return 1;
}

static cm_aarg *arg_list(P *p)
{
    cm_aarg *head = NULL, **tail = &head;
    if (!expect(p, T_LPAREN, "'('")) return NULL;
    while (cur(p)->type != T_RPAREN && !p->failed) {
        cm_aarg *a = cm_alloc(p->ctx->arena, sizeof *a);
        a->name = name(p, "a parameter name", &a->loc);
        if (!a->name) break;
        if (!expect(p, T_ASSIGN, "'=' after the parameter name")) break;
        a->val = value(p, "a value");
        *tail = a;
        tail = &a->next;
        if (cur(p)->type == T_COMMA) adv(p);
        else if (cur(p)->type != T_RPAREN) err_expected(p, "',' or ')'");
    }
    if (!p->failed) expect(p, T_RPAREN, "')'");
    return head;
}

static void hold_suffix(P *p, cm_acrit *c)
{
    if (is_kw(cur(p), "for")) {
        adv(p);
        /* "for at least 10 s" reads better to some; both forms mean the same */
        if (cur(p)->type == T_IDENT && !strcmp(cur(p)->text, "at") && peek(p, 1)->type == T_IDENT &&
            !strcmp(peek(p, 1)->text, "least")) {
            adv(p);
            adv(p);
        }
        c->hold = value(p, "a duration after 'for'");
        c->has_hold = true;
    }
}

static void criterion(P *p, cm_acrit *c)
{
    cm_token *t = cur(p);
    c->loc = loc_of(p, t);
    if (is_kw(t, "age") && peek(p, 1)->type == T_IDENT) {
        adv(p);
        if (is_kw(cur(p), "of")) adv(p);
        c->kind = CR_AGE;
        c->var = name(p, "a variable name", &c->var_loc);
        if (!c->var || !cmp_op(p, &c->op)) return;
        c->value = value(p, "a duration");
    } else if (is_kw(t, "elapsed")) {
        adv(p);
        c->kind = CR_ELAPSED;
        if (!cmp_op(p, &c->op)) return;
        c->value = value(p, "a duration");
    } else if (t->type == T_IDENT && !cm_is_keyword(t->text) && peek(p, 1)->type == T_LPAREN) {
        c->kind = CR_HANDLER;
        c->handler = t->text;
        c->var_loc = loc_of(p, t);
        adv(p);
        c->args = arg_list(p);
    } else {
        c->var = name(p, "a variable name, 'age', 'elapsed' or a test handler", &c->var_loc);
        if (!c->var) return;
        if (is_kw(cur(p), "within")) {
            adv(p);
            c->kind = CR_WITHIN;
            c->tol = value(p, "a tolerance");
            c->has_tol = true;
            if (!p->failed && !expect(p, T_IDENT, "'of'")) return;
            if (!p->failed && strcmp(peek(p, -1)->text, "of")) {
                p->pos--;
                err_expected(p, "'of'");
                return;
            }
            c->value = value(p, "a value");
        } else if (cur(p)->type == T_NEWLINE || cur(p)->type == T_EOF || is_kw(cur(p), "for")) {
            c->kind = CR_BOOLVAR;
        } else {
            c->kind = CR_CMP;
            if (!cmp_op(p, &c->op)) return;
            c->value = value(p, "a value");
            if (cur(p)->type == T_PLUSMINUS || is_kw(cur(p), "tolerance")) {
                adv(p);
                c->tol = value(p, "a tolerance");
                c->has_tol = true;
            }
        }
    }
    hold_suffix(p, c);
}

static cm_aexpr *expr_or(P *p);

static int expr_nodes; /* per condition: bounds the compiler's recursion */

static cm_aexpr *new_expr(P *p, cm_ekind k, cm_token *t)
{
    if (++expr_nodes == 2000 && !p->failed) {
        cm_error(p->ctx->diag, loc_of(p, t), "condition is too long (split it into several tests)");
        p->failed = 1;
    }
    cm_aexpr *e = cm_alloc(p->ctx->arena, sizeof *e);
    e->kind = k;
    e->loc = loc_of(p, t);
    return e;
}

static cm_aexpr *expr_primary(P *p, int depth)
{
    cm_token *t = cur(p);
    if (depth > 64) {
        if (!p->failed) cm_error(p->ctx->diag, loc_of(p, t), "condition nested too deeply");
        p->failed = 1;
        return NULL;
    }
    if (is_kw(t, "not")) {
        adv(p);
        cm_aexpr *e = new_expr(p, E_NOT, t);
        e->a = expr_primary(p, depth + 1);
        return e->a ? e : NULL;
    }
    if (t->type == T_LPAREN) {
        adv(p);
        cm_aexpr *e = expr_or(p);
        if (e && !expect(p, T_RPAREN, "')'")) return NULL;
        return e;
    }
    if (is_kw(t, "done")) { adv(p); return new_expr(p, E_DONE, t); }
    if (is_kw(t, "failed")) { adv(p); return new_expr(p, E_FAILED, t); }
    if (is_kw(t, "true")) { adv(p); return new_expr(p, E_TRUE, t); }
    if (is_kw(t, "false")) { adv(p); return new_expr(p, E_FALSE, t); }
    if (is_kw(t, "elapsed")) {
        adv(p);
        cm_aexpr *e = new_expr(p, E_ELAPSED, t);
        if (!cmp_op(p, &e->op)) return NULL;
        e->val = value(p, "a duration");
        return p->failed ? NULL : e;
    }
    if (t->type == T_IDENT && !cm_is_keyword(t->text)) {
        adv(p);
        cm_aexpr *e = new_expr(p, E_TEST, t);
        e->name = t->text;
        return e;
    }
    err_expected(p, "a test name, 'done', 'failed', 'elapsed', 'not' or '('");
    return NULL;
}

static int expr_depth;

static cm_aexpr *expr_and(P *p)
{
    cm_aexpr *l = expr_primary(p, expr_depth);
    while (l && !p->failed && is_kw(cur(p), "and")) {
        cm_token *t = cur(p);
        adv(p);
        cm_aexpr *e = new_expr(p, E_AND, t);
        e->a = l;
        e->b = expr_primary(p, expr_depth);
        if (!e->b) return NULL;
        l = e;
    }
    return l;
}

static cm_aexpr *expr_or(P *p)
{
    if (++expr_depth > 64) {
        if (!p->failed) cm_error(p->ctx->diag, loc_of(p, cur(p)), "condition nested too deeply");
        p->failed = 1;
        expr_depth--;
        return NULL;
    }
    cm_aexpr *l = expr_and(p);
    while (l && !p->failed && is_kw(cur(p), "or")) {
        cm_token *t = cur(p);
        adv(p);
        cm_aexpr *e = new_expr(p, E_OR, t);
        e->a = l;
        e->b = expr_and(p);
        if (!e->b) {
            l = NULL;
            break;
        }
        l = e;
    }
    expr_depth--;
    return l;
}

/* when COND -> [resume [deep]] TARGET */
static cm_atrans *transition(P *p, cm_token *kw)
{
    cm_atrans *tr = cm_alloc(p->ctx->arena, sizeof *tr);
    tr->loc = loc_of(p, kw);
    cm_token *first = cur(p);
    expr_depth = 0;
    expr_nodes = 0;
    tr->cond = expr_or(p);
    if (!tr->cond) {
        if (!p->failed) err_expected(p, "a condition");
        return NULL;
    }
    cm_token *last = peek(p, -1);
    if (last->line == first->line)
        tr->text = cm_strndup(p->ctx->arena, first->start, (size_t)(last->start + last->len - first->start));
    else
        tr->text = cm_strdup(p->ctx->arena, "(multi-line condition)");
    if (cur(p)->type == T_IDENT && !cm_is_keyword(cur(p)->text)) {
        err_expected(p, "'and', 'or' or '->'");
        return NULL;
    }
    if (!expect(p, T_ARROW, "'->' before the target state")) return NULL;
    if (is_kw(cur(p), "resume")) {
        adv(p);
        tr->history = HIST_SHALLOW;
        if (is_kw(cur(p), "deep") && peek(p, 1)->type == T_IDENT) {
            adv(p);
            tr->history = HIST_DEEP;
        }
    }
    /* target: name or path a/b/c */
    cm_loc l;
    char *n = name(p, "a target state", &l);
    if (!n) return NULL;
    char buf[512];
    snprintf(buf, sizeof buf, "%s", n);
    while (cur(p)->type == T_SLASH && !p->failed) {
        adv(p);
        char *m = name(p, "a state name after '/'", NULL);
        if (!m) return NULL;
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "/%s", m);
    }
    tr->target = cm_strdup(p->ctx->arena, buf);
    tr->target_loc = l;
    return tr;
}

static void time_model(P *p, cm_aaction *a)
{
    a->tm = TM_CYCLE;
    cm_token *t = cur(p);
    if (is_kw(t, "on")) {
        adv(p);
        if (is_kw(cur(p), "entry")) a->tm = TM_ENTRY;
        else if (is_kw(cur(p), "exit")) a->tm = TM_EXIT;
        else {
            err_expected(p, "'entry' or 'exit' after 'on'");
            return;
        }
        adv(p);
    } else if (is_kw(t, "every")) {
        adv(p);
        if (is_kw(cur(p), "cycle")) {
            adv(p);
            a->tm = TM_CYCLE;
        } else {
            a->tm = TM_EVERY;
            a->period = value(p, "'cycle' or a period after 'every'");
        }
    } else if (is_kw(t, "after")) {
        adv(p);
        a->tm = TM_AFTER;
        a->period = value(p, "a duration after 'after'");
    } else if (t->type != T_NEWLINE && t->type != T_EOF && t->type != T_RBRACE) {
        err_expected(p, "a time model ('on entry', 'on exit', 'every cycle', 'every T', 'after T') or end of line");
    }
}

static cm_aaction *action(P *p, cm_token *kw)
{
    cm_aaction *a = cm_alloc(p->ctx->arena, sizeof *a);
    a->loc = loc_of(p, kw);
    if (is_kw(cur(p), "set")) {
        adv(p);
        a->is_set = true;
        a->set_var = name(p, "a variable name", &a->set_var_loc);
        if (!a->set_var || !expect(p, T_ASSIGN, "'='")) return NULL;
        a->set_val = value(p, "a value");
    } else {
        a->behavior = name(p, "a behavior name or 'set'", &a->beh_loc);
        if (!a->behavior) return NULL;
        if (cur(p)->type == T_LPAREN) a->args = arg_list(p);
    }
    if (p->failed) return NULL;
    time_model(p, a);
    return p->failed ? NULL : a;
}

static cm_atest *test_decl(P *p, cm_token *kw)
{
    cm_atest *t = cm_alloc(p->ctx->arena, sizeof *t);
    t->loc = loc_of(p, kw);
    t->name = name(p, "a test name", &t->loc);
    if (!t->name || !expect(p, T_COLON, "':' after the test name")) return NULL;
    criterion(p, &t->crit);
    return p->failed ? NULL : t;
}

#define APPEND(head, tail, node) \
    do {                         \
        if (tail) tail->next = node; \
        else head = node;        \
        tail = node;             \
    } while (0)

static cm_astate *state_decl(P *p, int depth);

static void state_body(P *p, cm_astate *s, int depth)
{
    for (;;) {
        while (cur(p)->type == T_NEWLINE) adv(p);
        cm_token *t = cur(p);
        if (t->type == T_RBRACE) {
            adv(p);
            return;
        }
        if (t->type == T_EOF) {
            cm_error(p->ctx->diag, s->loc, "state '%s' is not closed: missing '}'", s->name);
            return;
        }
        if (is_kw(t, "state")) {
            adv(p);
            cm_astate *c = state_decl(p, depth + 1);
            if (c) APPEND(s->children, s->children_tail, c);
            if (p->failed) sync(p);
            continue;
        }
        adv(p);
        if (t->type != T_IDENT) {
            p->pos--;
            err_expected(p, "a statement (state, start, next, test, do, when)");
        } else if (!strcmp(t->text, "start")) {
            s->start = name(p, "a child state name", &s->start_loc);
        } else if (!strcmp(t->text, "next")) {
            if (is_kw(cur(p), "done")) {
                s->next_is_done = true;
                s->next_loc = loc_of(p, cur(p));
                adv(p);
            } else {
                s->next_state = name(p, "a state name", &s->next_loc);
                if (s->next_state) {
                    char buf[512];
                    snprintf(buf, sizeof buf, "%s", s->next_state);
                    while (cur(p)->type == T_SLASH && !p->failed) {
                        adv(p);
                        char *m = name(p, "a state name after '/'", NULL);
                        if (m) snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "/%s", m);
                    }
                    s->next_state = cm_strdup(p->ctx->arena, buf);
                }
            }
        } else if (!strcmp(t->text, "test")) {
            cm_atest *x = test_decl(p, t);
            if (x) APPEND(s->tests, s->tests_tail, x);
        } else if (!strcmp(t->text, "do")) {
            cm_aaction *x = action(p, t);
            if (x) APPEND(s->actions, s->actions_tail, x);
        } else if (!strcmp(t->text, "when")) {
            cm_atrans *x = transition(p, t);
            if (x) APPEND(s->trans, s->trans_tail, x);
        } else {
            cm_suggest sg;
            cm_suggest_init(&sg, t->text);
            const char *c[] = {"state", "start", "next", "test", "do", "when", NULL};
            for (int i = 0; c[i]; i++) cm_suggest_add(&sg, c[i]);
            char h[96];
            const char *where = (!strcmp(t->text, "param") || !strcmp(t->text, "use") || !strcmp(t->text, "input") ||
                                 !strcmp(t->text, "output") || !strcmp(t->text, "var") || !strcmp(t->text, "include") ||
                                 !strcmp(t->text, "abort"))
                                    ? " ('%s' is only allowed at the top level of a plan)"
                                    : NULL;
            if (where) {
                char msg[160];
                snprintf(msg, sizeof msg, where, t->text);
                cm_error(p->ctx->diag, loc_of(p, t), "unexpected '%s' inside state '%s'%s", t->text, s->name, msg);
            } else {
                cm_error(p->ctx->diag, loc_of(p, t), "unknown statement '%s' in state '%s'%s", t->text, s->name,
                         cm_suggest_hint(&sg, h, sizeof h));
            }
            p->failed = 1;
        }
        end_statement(p);
    }
}

static cm_astate *state_decl(P *p, int depth)
{
    cm_astate *s = cm_alloc(p->ctx->arena, sizeof *s);
    s->name = name(p, "a state name", &s->loc);
    if (!s->name) return NULL;
    if (depth >= CM_MAX_PARSE_DEPTH) {
        cm_error(p->ctx->diag, s->loc, "states nested too deeply (more than %d levels)", CM_MAX_PARSE_DEPTH);
        p->failed = 1;
        return NULL;
    }
    if (cur(p)->type == T_NEWLINE && peek(p, 1)->type == T_LBRACE) adv(p);
    if (!expect(p, T_LBRACE, "'{' after the state name")) return NULL;
    state_body(p, s, depth);
    return s;
}

static void var_decl(P *p, int kind)
{
    cm_aplan *pl = p->ctx->plan;
    cm_avar *v = cm_alloc(p->ctx->arena, sizeof *v);
    v->kind = kind;
    v->name = name(p, "a variable name", &v->loc);
    if (!v->name || !expect(p, T_COLON, "':' and a type (double, int, bool, string)")) return;
    v->type_loc = loc_of(p, cur(p));
    if (cur(p)->type != T_IDENT) {
        err_expected(p, "a type (double, int, bool, string)");
        return;
    }
    v->type_name = cur(p)->text;
    adv(p);
    cm_token *u = cur(p);
    if (u->type == T_IDENT && !cm_is_keyword(u->text) && u->line == peek(p, -1)->line) {
        cm_aval tmp = {0};
        unit_after_number(p, &tmp);
        v->unit = tmp.unit;
        if (!v->unit) return;
    }
    if (cur(p)->type == T_ASSIGN) {
        adv(p);
        v->init = value(p, "an initial value");
        v->has_init = true;
    }
    if (!p->failed) APPEND(pl->vars, pl->vars_tail, v);
}

static void top_level(P *p)
{
    cm_aplan *pl = p->ctx->plan;
    for (;;) {
        while (cur(p)->type == T_NEWLINE) adv(p);
        cm_token *t = cur(p);
        if (t->type == T_EOF) return;
        if (t->type == T_RBRACE) {
            cm_error(p->ctx->diag, loc_of(p, t), "unmatched '}'");
            adv(p);
            continue;
        }
        if (t->type != T_IDENT) {
            err_expected(p, "a statement (state, param, use, input, output, var, test, abort, include)");
            end_statement(p);
            continue;
        }
        adv(p);
        const char *k = t->text;
        if (!strcmp(k, "state")) {
            cm_astate *s = state_decl(p, 0);
            if (s) APPEND(pl->roots, pl->roots_tail, s);
            if (p->failed) sync(p);
            continue;
        } else if (!strcmp(k, "mission")) {
            if (cur(p)->type == T_STRING || cur(p)->type == T_IDENT) {
                if (!pl->mission_name) pl->mission_name = cur(p)->text;
                adv(p);
            } else err_expected(p, "a mission name");
        } else if (!strcmp(k, "include")) {
            cm_token *f = cur(p);
            if (f->type != T_STRING) err_expected(p, "a file name in quotes");
            else {
                adv(p);
                if (cur(p)->type == T_NEWLINE || cur(p)->type == T_EOF) {
                    char path[4096];
                    if (f->text[0] == '/' || !p->dir || !p->dir[0]) snprintf(path, sizeof path, "%s", f->text);
                    else snprintf(path, sizeof path, "%s/%s", p->dir, f->text);
                    cm_loc l = loc_of(p, f);
                    cm_parse_file(p->ctx, cm_strdup(p->ctx->arena, path), &l);
                }
            }
        } else if (!strcmp(k, "param")) {
            cm_aparam *x = cm_alloc(p->ctx->arena, sizeof *x);
            x->name = name(p, "a parameter name", &x->loc);
            x->depth = p->ctx->depth;
            if (x->name && expect(p, T_ASSIGN, "'=' after the parameter name")) {
                x->val = value(p, "a value");
                if (x->val.kind == V_PARAM && !p->failed) {
                    cm_error(p->ctx->diag, x->val.loc, "a parameter's value must be a constant, not another parameter");
                    p->failed = 1;
                }
                if (!p->failed) APPEND(pl->params, pl->params_tail, x);
            }
        } else if (!strcmp(k, "use")) {
            cm_ause *u = cm_alloc(p->ctx->arena, sizeof *u);
            u->name = name(p, "a plugin name", &u->loc);
            if (u->name) APPEND(pl->uses, pl->uses_tail, u);
        } else if (!strcmp(k, "input")) var_decl(p, 0);
        else if (!strcmp(k, "output")) var_decl(p, 1);
        else if (!strcmp(k, "var")) var_decl(p, 2);
        else if (!strcmp(k, "test")) {
            cm_atest *x = test_decl(p, t);
            if (x) APPEND(pl->tests, pl->tests_tail, x);
        } else if (!strcmp(k, "abort")) {
            if (is_kw(cur(p), "when")) {
                cm_token *w = cur(p);
                adv(p);
                cm_atrans *x = transition(p, w);
                if (x) {
                    x->loc = loc_of(p, t);
                    APPEND(pl->aborts, pl->aborts_tail, x);
                }
            } else err_expected(p, "'when' after 'abort'");
        } else if (!strcmp(k, "start")) {
            cm_loc l;
            char *n = name(p, "a root state name", &l);
            if (n) {
                pl->start = n;
                pl->start_loc = l;
            }
        } else {
            cm_suggest sg;
            cm_suggest_init(&sg, k);
            const char *c[] = {"state", "param", "use", "input", "output", "var", "test", "abort",
                               "include", "mission", "start", NULL};
            for (int i = 0; c[i]; i++) cm_suggest_add(&sg, c[i]);
            char h[96];
            if (!strcmp(k, "do") || !strcmp(k, "when") || !strcmp(k, "next"))
                cm_error(p->ctx->diag, loc_of(p, t), "'%s' is only allowed inside a state", k);
            else
                cm_error(p->ctx->diag, loc_of(p, t), "unknown statement '%s'%s", k, cm_suggest_hint(&sg, h, sizeof h));
            p->failed = 1;
        }
        end_statement(p);
    }
}

void cm_parse_text(cm_parse_ctx *ctx, const char *nm, const char *dir, const char *text, size_t len, cm_loc *inc)
{
    (void)inc;
    P p = {0};
    p.ctx = ctx;
    p.file = nm;
    p.dir = dir;
    p.order = ctx->file_counter++;
    cm_tokens toks = cm_lex(ctx->arena, ctx->diag, nm, p.order, text, len);
    p.t = toks.toks;
    p.n = toks.len;
    ctx->plan->n_files++;
    if (p.n) ctx->plan->n_lines += p.t[p.n - 1].line;
    top_level(&p);
    free(toks.toks);
}

void cm_parse_file(cm_parse_ctx *ctx, const char *path, cm_loc *inc)
{
    cm_loc here = inc ? *inc : (cm_loc){path, ctx->file_counter, 0, 0};
    for (int i = 0; i < ctx->depth; i++)
        if (!strcmp(ctx->stack[i], path)) {
            cm_error(ctx->diag, here, "'%s' includes itself (include cycle)", path);
            return;
        }
    if (ctx->depth >= 16) {
        cm_error(ctx->diag, here, "includes nested more than 16 deep");
        return;
    }
    struct stat sb;
    if (stat(path, &sb) || !S_ISREG(sb.st_mode)) {
        cm_error(ctx->diag, here, "cannot open '%s'%s", path, stat(path, &sb) ? "" : " (not a regular file)");
        return;
    }
    if (sb.st_size > 64L * 1024 * 1024) {
        cm_error(ctx->diag, here, "'%s' is larger than 64 MB", path);
        return;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        cm_error(ctx->diag, here, "cannot open '%s'", path);
        return;
    }
    size_t cap = 65536, n = 0;
    char *buf = malloc(cap);
    if (!buf) abort();
    size_t r;
    while ((r = fread(buf + n, 1, cap - n, f)) > 0) {
        n += r;
        if (n == cap) {
            cap *= 2;
            buf = realloc(buf, cap);
            if (!buf) abort();
        }
    }
    fclose(f);
    char *dir = cm_strdup(ctx->arena, path);
    char *slash = strrchr(dir, '/');
    if (slash) *slash = 0;
    else dir[0] = 0;
    ctx->stack[ctx->depth++] = path;
    cm_parse_text(ctx, path, dir, buf, n, inc);
    ctx->depth--;
    free(buf);
}
