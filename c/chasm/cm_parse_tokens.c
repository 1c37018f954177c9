/* Parser, token level: reserved words, expectations, names, error recovery. */
#include "chasm/cm_parse_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Reserved words cannot name anything. Other words of the language (entry,
 * exit, cycle, every, after, for, within, of, tolerance, age, deep) are only
 * special where they are expected, so states may be called `after` or `deep`. */
static const char *keywords[] = {
    "include", "param", "use", "input", "output", "var", "test", "abort", "when", "start", "next",
    "state", "do", "set", "and", "or", "not", "true", "false", "resume", "done", "failed", "elapsed", NULL};

int cm_is_keyword(const char *s)
{
    for (int i = 0; keywords[i]; i++)
        if (!strcmp(s, keywords[i])) return 1;
    return 0;
}

static void describe(cm_token *t, char *buf, size_t n)
{
    if (t->type == T_IDENT) snprintf(buf, n, "'%s'", t->text);
    else if (t->type == T_NUMBER) snprintf(buf, n, "number '%.*s'", t->len, t->start);
    else snprintf(buf, n, "%s", cm_tok_name(t->type));
}

void cm_p_err_expected(P *p, const char *what)
{
    if (p->failed) return;
    char b[128];
    describe(cur(p), b, sizeof b);
    cm_error(p->ctx->diag, loc_of(p, cur(p)), "expected %s, found %s", what, b);
    p->failed = 1;
}

int cm_p_expect(P *p, cm_tok_type ty, const char *what)
{
    if (cur(p)->type == ty) {
        adv(p);
        return 1;
    }
    cm_p_err_expected(p, what);
    return 0;
}

/* A user-chosen name: an identifier that is not a reserved word. */
char *cm_p_name(P *p, const char *what, cm_loc *loc)
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
    cm_p_err_expected(p, what);
    return NULL;
}

/* Skips the rest of a statement, including any block it opened. */
void cm_p_sync(P *p)
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

void cm_p_end_statement(P *p)
{
    if (!p->failed) {
        cm_token *t = cur(p);
        if (t->type == T_NEWLINE) adv(p);
        else if (t->type != T_EOF && t->type != T_RBRACE) cm_p_err_expected(p, "end of line");
    }
    if (p->failed) cm_p_sync(p);
}
