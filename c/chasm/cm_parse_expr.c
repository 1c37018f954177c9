/* Parser, conditions: `not`, `and`, `or`, parentheses, test names, `done`,
 * `failed`, `elapsed`. Depth and size are bounded so the compiler's recursion is. */
#include "chasm/cm_parse_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static cm_aexpr *new_expr(P *p, cm_ekind k, cm_token *t)
{
    if (++p->expr_nodes == 2000 && !p->failed) {
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
        cm_aexpr *e = cm_p_expr_or(p);
        if (e && !cm_p_expect(p, T_RPAREN, "')'")) return NULL;
        return e;
    }
    if (is_kw(t, "done")) { adv(p); return new_expr(p, E_DONE, t); }
    if (is_kw(t, "failed")) { adv(p); return new_expr(p, E_FAILED, t); }
    if (is_kw(t, "true")) { adv(p); return new_expr(p, E_TRUE, t); }
    if (is_kw(t, "false")) { adv(p); return new_expr(p, E_FALSE, t); }
    if (is_kw(t, "elapsed")) {
        adv(p);
        cm_aexpr *e = new_expr(p, E_ELAPSED, t);
        if (!cm_p_cmp_op(p, &e->op)) return NULL;
        e->val = cm_p_value(p, "a duration");
        return p->failed ? NULL : e;
    }
    if (t->type == T_IDENT && !cm_is_keyword(t->text)) {
        adv(p);
        cm_aexpr *e = new_expr(p, E_TEST, t);
        e->name = t->text;
        return e;
    }
    cm_p_err_expected(p, "a test name, 'done', 'failed', 'elapsed', 'not' or '('");
    return NULL;
}

static cm_aexpr *expr_and(P *p)
{
    cm_aexpr *l = expr_primary(p, p->expr_depth);
    while (l && !p->failed && is_kw(cur(p), "and")) {
        cm_token *t = cur(p);
        adv(p);
        cm_aexpr *e = new_expr(p, E_AND, t);
        e->a = l;
        e->b = expr_primary(p, p->expr_depth);
        if (!e->b) return NULL;
        l = e;
    }
    return l;
}

cm_aexpr *cm_p_expr_or(P *p)
{
    if (++p->expr_depth > 64) {
        if (!p->failed) cm_error(p->ctx->diag, loc_of(p, cur(p)), "condition nested too deeply");
        p->failed = 1;
        p->expr_depth--;
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
    p->expr_depth--;
    return l;
}
