/* Parser, statements: plans, states, declarations, transitions, actions and
 * includes. Values and conditions are in cm_parse_values.c / cm_parse_expr.c. */
#include "chasm/cm_parser.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "chasm/cm_parse_internal.h"

/* when COND -> [resume [deep]] TARGET */
static cm_atrans *transition(P *p, cm_token *kw)
{
    cm_atrans *tr = cm_alloc(p->ctx->arena, sizeof *tr);
    tr->loc = loc_of(p, kw);
    cm_token *first = cur(p);
    p->expr_depth = 0;
    p->expr_nodes = 0;
    tr->cond = cm_p_expr_or(p);
    if (!tr->cond) {
        if (!p->failed) cm_p_err_expected(p, "a condition");
        return NULL;
    }
    cm_token *last = peek(p, -1);
    if (last->line == first->line)
        tr->text = cm_strndup(p->ctx->arena, first->start, (size_t)(last->start + last->len - first->start));
    else
        tr->text = cm_strdup(p->ctx->arena, "(multi-line condition)");
    if (cur(p)->type == T_IDENT && !cm_is_keyword(cur(p)->text)) {
        cm_p_err_expected(p, "'and', 'or' or '->'");
        return NULL;
    }
    if (!cm_p_expect(p, T_ARROW, "'->' before the target state")) return NULL;
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
    char *n = cm_p_name(p, "a target state", &l);
    if (!n) return NULL;
    /* a path of any length (no buffer to cut it) */
    const char *path = n;
    while (cur(p)->type == T_SLASH && !p->failed) {
        adv(p);
        char *m = cm_p_name(p, "a state name after '/'", NULL);
        if (!m) return NULL;
        path = cm_sprintf(p->ctx->arena, "%s/%s", path, m);
    }
    tr->target = (char *)path;
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
            cm_p_err_expected(p, "'entry' or 'exit' after 'on'");
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
            a->period = cm_p_value(p, "'cycle' or a period after 'every'");
        }
    } else if (is_kw(t, "after")) {
        adv(p);
        a->tm = TM_AFTER;
        a->period = cm_p_value(p, "a duration after 'after'");
    } else if (t->type != T_NEWLINE && t->type != T_EOF && t->type != T_RBRACE) {
        cm_p_err_expected(p, "a time model ('on entry', 'on exit', 'every cycle', 'every T', 'after T') or end of line");
    }
}

static cm_aaction *action(P *p, cm_token *kw)
{
    cm_aaction *a = cm_alloc(p->ctx->arena, sizeof *a);
    a->loc = loc_of(p, kw);
    if (is_kw(cur(p), "set")) {
        adv(p);
        a->is_set = true;
        a->set_var = cm_p_name(p, "a variable name", &a->set_var_loc);
        if (!a->set_var || !cm_p_expect(p, T_ASSIGN, "'='")) return NULL;
        a->set_val = cm_p_value(p, "a value");
    } else {
        a->behavior = cm_p_name(p, "a behavior name or 'set'", &a->beh_loc);
        if (!a->behavior) return NULL;
        if (cur(p)->type == T_LPAREN) a->args = cm_p_arg_list(p);
    }
    if (p->failed) return NULL;
    time_model(p, a);
    return p->failed ? NULL : a;
}

static cm_atest *test_decl(P *p, cm_token *kw)
{
    cm_atest *t = cm_alloc(p->ctx->arena, sizeof *t);
    t->loc = loc_of(p, kw);
    t->name = cm_p_name(p, "a test name", &t->loc);
    if (!t->name || !cm_p_expect(p, T_COLON, "':' after the test name")) return NULL;
    cm_p_criterion(p, &t->crit);
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
            if (p->failed) cm_p_sync(p);
            continue;
        }
        adv(p);
        if (t->type != T_IDENT) {
            p->pos--;
            cm_p_err_expected(p, "a statement (state, start, next, test, do, when)");
        } else if (!strcmp(t->text, "start")) {
            s->start = cm_p_name(p, "a child state name", &s->start_loc);
        } else if (!strcmp(t->text, "next")) {
            if (is_kw(cur(p), "done")) {
                s->next_is_done = true;
                s->next_loc = loc_of(p, cur(p));
                adv(p);
            } else {
                s->next_state = cm_p_name(p, "a state name", &s->next_loc);
                while (s->next_state && cur(p)->type == T_SLASH && !p->failed) {
                    adv(p);
                    char *m = cm_p_name(p, "a state name after '/'", NULL);
                    if (m) s->next_state = cm_sprintf(p->ctx->arena, "%s/%s", s->next_state, m);
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
        cm_p_end_statement(p);
    }
}

static cm_astate *state_decl(P *p, int depth)
{
    cm_astate *s = cm_alloc(p->ctx->arena, sizeof *s);
    s->name = cm_p_name(p, "a state name", &s->loc);
    if (!s->name) return NULL;
    if (depth >= CM_MAX_PARSE_DEPTH) {
        cm_error(p->ctx->diag, s->loc, "states nested too deeply (more than %d levels, CHASM_MAX_STATE_DEPTH)", CM_MAX_PARSE_DEPTH);
        p->failed = 1;
        return NULL;
    }
    if (cur(p)->type == T_NEWLINE && peek(p, 1)->type == T_LBRACE) adv(p);
    if (!cm_p_expect(p, T_LBRACE, "'{' after the state name")) return NULL;
    state_body(p, s, depth);
    return s;
}

static void var_decl(P *p, int kind)
{
    cm_aplan *pl = p->ctx->plan;
    cm_avar *v = cm_alloc(p->ctx->arena, sizeof *v);
    v->kind = kind;
    v->name = cm_p_name(p, "a variable name", &v->loc);
    if (!v->name || !cm_p_expect(p, T_COLON, "':' and a type (double, int, bool, string, messages)")) return;
    v->type_loc = loc_of(p, cur(p));
    if (cur(p)->type != T_IDENT) {
        cm_p_err_expected(p, "a type (double, int, bool, string, messages)");
        return;
    }
    v->type_name = cur(p)->text;
    adv(p);
    if (cur(p)->type == T_LPAREN && cur(p)->line == peek(p, -1)->line) {
        /* `messages(256)`: a stream's capacity (checked with the type) */
        v->cap_loc = loc_of(p, cur(p));
        adv(p);
        v->capacity = cm_p_value(p, "a capacity (a number of messages)");
        v->has_capacity = true;
        if (p->failed || !cm_p_expect(p, T_RPAREN, "')' after the capacity")) return;
    }
    cm_token *u = cur(p);
    if (u->type == T_IDENT && !cm_is_keyword(u->text) && u->line == peek(p, -1)->line) {
        cm_aval tmp = {0};
        cm_p_unit_after_number(p, &tmp);
        v->unit = tmp.unit;
        if (!v->unit) return;
    }
    if (cur(p)->type == T_ASSIGN) {
        adv(p);
        v->init = cm_p_value(p, "an initial value");
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
            cm_p_err_expected(p, "a statement (state, param, use, input, output, var, test, abort, include)");
            cm_p_end_statement(p);
            continue;
        }
        adv(p);
        const char *k = t->text;
        if (!strcmp(k, "state")) {
            cm_astate *s = state_decl(p, 0);
            if (s) APPEND(pl->roots, pl->roots_tail, s);
            if (p->failed) cm_p_sync(p);
            continue;
        } else if (!strcmp(k, "mission")) {
            if (cur(p)->type == T_STRING || cur(p)->type == T_IDENT) {
                if (!pl->mission_name) pl->mission_name = cur(p)->text;
                adv(p);
            } else cm_p_err_expected(p, "a mission name");
        } else if (!strcmp(k, "include")) {
            cm_token *f = cur(p);
            if (f->type != T_STRING) cm_p_err_expected(p, "a file name in quotes");
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
            x->name = cm_p_name(p, "a parameter name", &x->loc);
            x->depth = p->ctx->depth;
            if (x->name && cm_p_expect(p, T_ASSIGN, "'=' after the parameter name")) {
                x->val = cm_p_value(p, "a value");
                if (x->val.kind == V_PARAM && !p->failed) {
                    cm_error(p->ctx->diag, x->val.loc, "a parameter's value must be a constant, not another parameter");
                    p->failed = 1;
                }
                if (!p->failed) APPEND(pl->params, pl->params_tail, x);
            }
        } else if (!strcmp(k, "use")) {
            cm_ause *u = cm_alloc(p->ctx->arena, sizeof *u);
            u->name = cm_p_name(p, "a plugin name", &u->loc);
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
            } else cm_p_err_expected(p, "'when' after 'abort'");
        } else if (!strcmp(k, "start")) {
            cm_loc l;
            char *n = cm_p_name(p, "a root state name", &l);
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
        cm_p_end_statement(p);
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
    if (ctx->depth >= CHASM_MAX_INCLUDE_DEPTH) {
        cm_error(ctx->diag, here, "includes nested more than %d deep (CHASM_MAX_INCLUDE_DEPTH)", CHASM_MAX_INCLUDE_DEPTH);
        return;
    }
    struct stat sb;
    if (stat(path, &sb) || !S_ISREG(sb.st_mode)) {
        cm_error(ctx->diag, here, "cannot open '%s'%s", path, stat(path, &sb) ? "" : " (not a regular file)");
        return;
    }
    if (sb.st_size > CHASM_MAX_FILE_BYTES) {
        cm_error(ctx->diag, here, "'%s' is larger than %d bytes (CHASM_MAX_FILE_BYTES)", path, CHASM_MAX_FILE_BYTES);
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
