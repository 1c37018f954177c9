/* Parser, values and test criteria: numbers with units, strings, parameters,
 * comparisons, argument lists, `within`, `age`, `for`. */
#include "chasm/cm_parse_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chasm/cm_units.h"

/* Words that may follow a number and so are never read as its unit. */
static const char *after_number[] = {"of", "for", "tolerance", "on", "every", "after", "and", "or", "at", NULL};

static int stops_unit(const char *s)
{
    for (int i = 0; after_number[i]; i++)
        if (!strcmp(s, after_number[i])) return 1;
    return 0;
}

/* unit := IDENT [ '/' IDENT ], only when an identifier follows a number. */
void cm_p_unit_after_number(P *p, cm_aval *v)
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

cm_aval cm_p_value(P *p, const char *what)
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
        cm_p_unit_after_number(p, &v);
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
    default: cm_p_err_expected(p, what); return v;
    }
}

int cm_p_cmp_op(P *p, cm_cmp *op)
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
    default: cm_p_err_expected(p, "a comparison (<, <=, >, >=, ==, !=)"); return 0;
    }
    adv(p);
    return 1;
}

cm_aarg *cm_p_arg_list(P *p)
{
    cm_aarg *head = NULL, **tail = &head;
    if (!cm_p_expect(p, T_LPAREN, "'('")) return NULL;
    while (cur(p)->type != T_RPAREN && !p->failed) {
        cm_aarg *a = cm_alloc(p->ctx->arena, sizeof *a);
        a->name = cm_p_name(p, "a parameter name", &a->loc);
        if (!a->name) break;
        if (!cm_p_expect(p, T_ASSIGN, "'=' after the parameter name")) break;
        a->val = cm_p_value(p, "a value");
        *tail = a;
        tail = &a->next;
        if (cur(p)->type == T_COMMA) adv(p);
        else if (cur(p)->type != T_RPAREN) cm_p_err_expected(p, "',' or ')'");
    }
    if (!p->failed) cm_p_expect(p, T_RPAREN, "')'");
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
        c->hold = cm_p_value(p, "a duration after 'for'");
        c->has_hold = true;
    }
}

void cm_p_criterion(P *p, cm_acrit *c)
{
    cm_token *t = cur(p);
    c->loc = loc_of(p, t);
    if (is_kw(t, "age") && peek(p, 1)->type == T_IDENT) {
        adv(p);
        if (is_kw(cur(p), "of")) adv(p);
        c->kind = CR_AGE;
        c->var = cm_p_name(p, "a variable name", &c->var_loc);
        if (!c->var || !cm_p_cmp_op(p, &c->op)) return;
        c->value = cm_p_value(p, "a duration");
    } else if (is_kw(t, "elapsed")) {
        adv(p);
        c->kind = CR_ELAPSED;
        if (!cm_p_cmp_op(p, &c->op)) return;
        c->value = cm_p_value(p, "a duration");
    } else if (t->type == T_IDENT && !cm_is_keyword(t->text) && peek(p, 1)->type == T_LPAREN) {
        c->kind = CR_HANDLER;
        c->handler = t->text;
        c->var_loc = loc_of(p, t);
        adv(p);
        c->args = cm_p_arg_list(p);
    } else {
        c->var = cm_p_name(p, "a variable name, 'age', 'elapsed' or a test handler", &c->var_loc);
        if (!c->var) return;
        if (is_kw(cur(p), "within")) {
            adv(p);
            c->kind = CR_WITHIN;
            c->tol = cm_p_value(p, "a tolerance");
            c->has_tol = true;
            if (!p->failed && !cm_p_expect(p, T_IDENT, "'of'")) return;
            if (!p->failed && strcmp(peek(p, -1)->text, "of")) {
                p->pos--;
                cm_p_err_expected(p, "'of'");
                return;
            }
            c->value = cm_p_value(p, "a value");
        } else if (cur(p)->type == T_NEWLINE || cur(p)->type == T_EOF || is_kw(cur(p), "for")) {
            c->kind = CR_BOOLVAR;
        } else {
            c->kind = CR_CMP;
            if (!cm_p_cmp_op(p, &c->op)) return;
            c->value = cm_p_value(p, "a value");
            if (cur(p)->type == T_PLUSMINUS || is_kw(cur(p), "tolerance")) {
                adv(p);
                c->tol = cm_p_value(p, "a tolerance");
                c->has_tol = true;
            }
        }
    }
    hold_suffix(p, c);
}
