/* Parameter overrides (`chasm -D name=value`, chasm-manager -D, any caller of
 * chasm_options.param_*): a value, never plan text. The value must lex to
 * exactly one value (a number with an optional unit, a string in quotes,
 * true or false) with nothing else around it (no newline, no '#', no '}'),
 * and the name must be a parameter the plan declares, with a value of the
 * same kind and unit dimension. Errors are "<-D name>:1:col: error: ...". */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chasm/cm_overrides.h"
#include "chasm/cm_parse_internal.h"

static const char *kind_name(const cm_aval *v)
{
    switch (v->kind) {
    case V_NUMBER: return v->unit && v->unit->dim != CM_DIM_NONE ? cm_dim_name(v->unit->dim) : "a plain number";
    case V_STRING: return "a string";
    case V_BOOL: return "true or false";
    case V_NAME: return "a name";
    default: return "something else";
    }
}

static int valid_name(const char *s)
{
    if (!s || !(s[0] == '_' || (s[0] >= 'a' && s[0] <= 'z') || (s[0] >= 'A' && s[0] <= 'Z'))) return 0;
    for (const char *p = s; *p; p++)
        if (!(*p == '_' || (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9'))) return 0;
    return 1;
}

void cm_parse_override(cm_parse_ctx *ctx, const char *name, const char *value)
{
    const char *file = cm_sprintf(ctx->arena, "<-D %.60s%s>", name ? name : "", name && strlen(name) > 60 ? "..." : "");
    int order = ctx->file_counter++;
    cm_loc at = {file, order, 1, 1};
    if (!valid_name(name)) {
        cm_error(ctx->diag, at, "-D wants NAME=VALUE with NAME a parameter name (letters, digits, '_')");
        return;
    }
    if (!value) value = "";
    size_t n = strlen(value);
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)value[i] < 0x20 || (unsigned char)value[i] == 0x7f) {
            at.col = (int)i + 1;
            cm_error(ctx->diag, at, "the value of -D %s contains a control character (byte 0x%02x): a value is one line",
                     name, (unsigned char)value[i]);
            return;
        }
    size_t before = ctx->diag->len;
    cm_tokens toks = cm_lex(ctx->arena, ctx->diag, file, order, value, n);
    if (ctx->diag->len != before) {
        free(toks.toks);
        return;
    }
    P p = {0};
    p.ctx = ctx;
    p.file = file;
    p.order = order;
    p.t = toks.toks;
    p.n = toks.len;
    cm_aval v = {0};
    if (cur(&p)->type == T_EOF) {
        cm_error(ctx->diag, at, "-D %s has no value (write e.g. -D %s='12 m')", name, name);
        free(toks.toks);
        return;
    }
    v = cm_p_value(&p, "a value: a number with its unit, a string in quotes, true or false");
    if (!p.failed && v.kind == V_PARAM) {
        cm_error(ctx->diag, v.loc, "the value of -D %s must be a constant (a number with its unit, a string in quotes, "
                                   "true or false), not the parameter '$%s'", name, v.str);
        p.failed = 1;
    }
    /* Exactly one value and nothing after it; a comment ('#') the lexer
     * skipped counts as something after it. */
    cm_token *end = cur(&p);
    const char *rest = p.pos ? peek(&p, -1)->start + peek(&p, -1)->len : value;
    while (rest < value + n && *rest == ' ') rest++;
    if (!p.failed && (end->type != T_EOF || rest != value + n)) {
        at.col = (int)(rest - value) + 1;
        cm_error(ctx->diag, at, "-D %s takes one value; '%s' has more after it (a value is never plan text)", name, value);
        p.failed = 1;
    }
    free(toks.toks);
    if (p.failed) return;
    cm_aparam *x = cm_alloc(ctx->arena, sizeof *x);
    x->name = cm_strdup(ctx->arena, name);
    x->loc = at;
    x->val = v;
    x->depth = 0;
    x->is_override = true;
    cm_aplan *pl = ctx->plan;
    if (pl->params_tail) pl->params_tail->next = x;
    else pl->params = x;
    pl->params_tail = x;
}

void cm_check_overrides(cm_diag *d, const cm_aplan *plan)
{
    for (const cm_aparam *o = plan->params; o; o = o->next) {
        if (!o->is_override) continue;
        const cm_aparam *decl = NULL;
        cm_suggest sg;
        cm_suggest_init(&sg, o->name);
        for (const cm_aparam *q = plan->params; q; q = q->next) {
            if (q->is_override) continue;
            cm_suggest_add(&sg, q->name);
            if (!strcmp(q->name, o->name) && (!decl || q->depth < decl->depth)) decl = q;
        }
        if (!decl) {
            char h[96];
            const char *hint = cm_suggest_hint(&sg, h, sizeof h);
            cm_error(d, o->loc, "-D %s: the plan has no parameter '%s'%s", o->name, o->name,
                     *hint ? hint : " (only parameters declared with `param NAME = VALUE` can be overridden)");
            continue;
        }
        const cm_aval *a = &o->val, *b = &decl->val;
        int dim_a = a->unit ? (int)a->unit->dim : (int)CM_DIM_NONE, dim_b = b->unit ? (int)b->unit->dim : (int)CM_DIM_NONE;
        if (a->kind != b->kind || (a->kind == V_NUMBER && dim_a != dim_b)) {
            cm_error(d, o->loc, "-D %s: the value is %s%s%s%s, but the plan's '%s' is %s (%s:%d:%d)", o->name,
                     kind_name(a), a->kind == V_NAME ? " ('" : "", a->kind == V_NAME ? a->str : "",
                     a->kind == V_NAME ? "')" : "", o->name, kind_name(b), decl->loc.file, decl->loc.line,
                     decl->loc.col);
        }
    }
}
