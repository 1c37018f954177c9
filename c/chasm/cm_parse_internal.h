/* Parser internals shared by cm_parser.c (statements), cm_parse_values.c
 * (values, criteria), cm_parse_expr.c (conditions) and cm_parse_tokens.c
 * (token helpers, error recovery). Not part of libchasm's API. */
#ifndef CM_PARSE_INTERNAL_H
#define CM_PARSE_INTERNAL_H
#include <string.h>

#include "chasm/cm_lexer.h"
#include "chasm/cm_parser.h"

/* The state of one file's parse. */
typedef struct {
    cm_parse_ctx *ctx;
    cm_token *t;
    size_t pos, n;
    const char *file;
    const char *dir;
    int order;
    int failed;      /* current statement had an error: skip to its end */
    int expr_nodes;  /* per condition: bounds the compiler's recursion */
    int expr_depth;
} P;

static inline cm_token *cur(P *p) { return &p->t[p->pos]; }
static inline cm_token *peek(P *p, int k)
{
    size_t i = p->pos + (size_t)k;
    return &p->t[i < p->n ? i : p->n - 1];
}
static inline cm_loc loc_of(P *p, cm_token *t) { return (cm_loc){p->file, p->order, t->line, t->col}; }
static inline void adv(P *p)
{
    if (p->pos + 1 < p->n) p->pos++;
}
static inline int is_kw(cm_token *t, const char *kw) { return t->type == T_IDENT && !strcmp(t->text, kw); }

/* Token level (cm_parse_tokens.c). After an error, p->failed is set and the
 * statement is skipped by cm_p_end_statement / cm_p_sync. */
void cm_p_err_expected(P *p, const char *what);
int cm_p_expect(P *p, cm_tok_type ty, const char *what);
char *cm_p_name(P *p, const char *what, cm_loc *loc); /* a user-chosen name, not a reserved word */
void cm_p_sync(P *p);
void cm_p_end_statement(P *p);

/* Values and criteria (cm_parse_values.c). */
cm_aval cm_p_value(P *p, const char *what);
void cm_p_unit_after_number(P *p, cm_aval *v); /* an optional unit right after a number */
cm_aarg *cm_p_arg_list(P *p);
int cm_p_cmp_op(P *p, cm_cmp *op); /* < <= > >= == != */
void cm_p_criterion(P *p, cm_acrit *c);

/* Conditions (cm_parse_expr.c). Reset p->expr_nodes/expr_depth per condition. */
cm_aexpr *cm_p_expr_or(P *p);
#endif
