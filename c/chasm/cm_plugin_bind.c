/* Binding at compile time: find the plugin of a behavior or test handler
 * named in the plan, and bind the plan's arguments against its parameter
 * schema (type, unit, range, required, variables and the one-writer rule). */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "chasm/cm_compile.h"

static void check_limits(cm_cc *cc, cm_binding *b, const char *item, const cm_aarg *args, cm_loc item_loc, cm_state *st);

cm_plugin *cm_find_plugin_of(cm_cc *cc, const char *item, int want_test, cm_loc loc, const void **spec)
{
    chasm_machine *m = cc->m;
    const char *dot = strrchr(item, '.');
    const char *bare = dot ? dot + 1 : item;
    cm_plugin *found = NULL;
    const char *kind = want_test ? "test handler" : "behavior";
    for (int i = 0; i < m->n_plugins; i++) {
        cm_plugin *p = &m->plugins[i];
        if (dot && (strlen(p->name) != (size_t)(dot - item) || strncmp(p->name, item, (size_t)(dot - item)))) continue;
        const chasm_plugin_descriptor *d = p->current->desc;
        size_t n = want_test ? d->n_tests : d->n_behaviors;
        for (size_t k = 0; k < n; k++) {
            const char *nm = want_test ? d->tests[k].name : d->behaviors[k].name;
            if (strcmp(nm, bare)) continue;
            if (found) {
                cm_error(cc->d, loc, "%s '%s' is in plugins '%s' and '%s': write '%s.%s'", kind, bare, found->name,
                         p->name, found->name, bare);
                return NULL;
            }
            found = p;
            *spec = want_test ? (const void *)&d->tests[k] : (const void *)&d->behaviors[k];
        }
    }
    if (found) return found;
    cm_suggest sg;
    cm_suggest_init(&sg, bare);
    for (int i = 0; i < m->n_plugins; i++) {
        const chasm_plugin_descriptor *d = m->plugins[i].current->desc;
        size_t n = want_test ? d->n_tests : d->n_behaviors;
        for (size_t k = 0; k < n; k++) cm_suggest_add(&sg, want_test ? d->tests[k].name : d->behaviors[k].name);
    }
    char h[96];
    const char *hint = cm_suggest_hint(&sg, h, sizeof h);
    if (*hint) cm_error(cc->d, loc, "unknown %s '%s'%s", kind, item, hint);
    else if (cc->plan->uses && m->n_plugins == 0)
        /* the plan names plugins, but none loaded: their errors came first */
        cm_error(cc->d, loc, "unknown %s '%s' (no plugin named by `use` loaded: see the error above)", kind, item);
    else if (!m->n_plugins && !want_test)
        cm_error(cc->d, loc, "unknown behavior '%s' (the plan uses no plugins: add `use PLUGIN`; the built-in action is `set`)", item);
    else cm_error(cc->d, loc, "unknown %s '%s' (not in any plugin named by `use`)", kind, item);
    return NULL;
}

/* ------------------------------------------------------------ a plugin's own limits */

/* What the plugin's check sees: the plan's parameters; no variables (it runs
 * at load, before anything has a value), no writes. */
static double no_read_d(const chasm_ctx *c, int s) { (void)c; (void)s; return 0.0; }
static int64_t no_read_i(const chasm_ctx *c, int s) { (void)c; (void)s; return 0; }
static int no_read_b(const chasm_ctx *c, int s) { (void)c; (void)s; return 0; }
static const char *no_read_s(const chasm_ctx *c, int s) { (void)c; (void)s; return ""; }
static double no_age(const chasm_ctx *c, int s) { (void)c; (void)s; return 1e300; }
static void no_write_d(chasm_ctx *c, int s, double v) { (void)c; (void)s; (void)v; }
static void no_write_i(chasm_ctx *c, int s, int64_t v) { (void)c; (void)s; (void)v; }
static void no_write_b(chasm_ctx *c, int s, int v) { (void)c; (void)s; (void)v; }
static void no_write_s(chasm_ctx *c, int s, const char *v) { (void)c; (void)s; (void)v; }
static void no_log(chasm_ctx *c, const char *m) { (void)c; (void)m; }
static const void *no_next(chasm_ctx *c, int s, size_t *len) { (void)c; (void)s; if (len) *len = 0; return NULL; }
static int no_post(chasm_ctx *c, int s, const void *d, size_t n) { (void)c; (void)s; (void)d; (void)n; return -1; }

/* The plugin's name of the behavior or test handler whose schema is specs. */
static const char *spec_name(const chasm_plugin_descriptor *d, const chasm_param_spec *specs, const char *item)
{
    const char *dot = strrchr(item, '.');
    const char *bare = dot ? dot + 1 : item, *first = NULL;
    for (size_t k = 0; k < d->n_behaviors + d->n_tests; k++) {
        int beh = k < d->n_behaviors;
        const char *nm = beh ? d->behaviors[k].name : d->tests[k - d->n_behaviors].name;
        const chasm_param_spec *ps = beh ? d->behaviors[k].params : d->tests[k - d->n_behaviors].params;
        if (ps != specs) continue;
        if (!strncmp(nm, bare, strlen(nm)) && !isalnum((unsigned char)bare[strlen(nm)]) && bare[strlen(nm)] != '_')
            return nm;
        if (!first) first = nm;
    }
    return first ? first : bare;
}

/* A limit the schema cannot state (chasm_plugin.h, CHASM_PLUGIN_CHECK) is a
 * load error at the parameter the plugin names. */
static void check_limits(cm_cc *cc, cm_binding *b, const char *item, const cm_aarg *args, cm_loc item_loc, cm_state *st)
{
    static const chasm_host_api api = {NULL, NULL, NULL, NULL, no_read_d, no_read_i, no_read_b, no_read_s, no_age,
                                       no_write_d, no_write_i, no_write_b, no_write_s, no_log, no_next, no_post, NULL};
    chasm_host_api full = api;
    full.param_double = cm_host_api.param_double;
    full.param_int = cm_host_api.param_int;
    full.param_bool = cm_host_api.param_bool;
    full.param_string = cm_host_api.param_string;
    full.param_given = cm_host_api.param_given;
    cm_ext x = {0};
    x.c.api = &full;
    x.c.state_path = st ? st->path : "";
    x.c.engine = &x;
    x.m = cc->m;
    x.b = b;
    const char *name = spec_name(b->ver->desc, b->specs, item);
    int slot = -1;
    char why[256] = "";
    if (!b->ver->check(name, &x.c, &slot, why, sizeof why)) return;
    why[sizeof why - 1] = 0;
    if (slot < 0 || slot >= b->n_slots) {
        cm_error(cc->d, item_loc, "'%s': %s", item, why[0] ? why : "refused by its plugin");
        return;
    }
    cm_loc loc = item_loc;
    for (const cm_aarg *g = args; g; g = g->next)
        if (!strcmp(g->name, b->specs[slot].name)) loc = g->val.loc;
    cm_error(cc->d, loc, "parameter '%s' of '%s': %s", b->specs[slot].name, item, why[0] ? why : "refused by its plugin");
}

static const char *slot_kind_name(chasm_slot_kind k) { return k == CHASM_WRITES ? "writes" : "reads"; }

cm_binding *cm_bind(cm_cc *cc, cm_arena *a, cm_plugin_version *ver, const char *item, const chasm_param_spec *specs,
                    size_t n, const cm_aarg *args, cm_loc item_loc, cm_state *st, bool record_writers)
{
    size_t before = cc->d->len;
    cm_binding *b = cm_alloc(a, sizeof *b);
    b->ver = ver;
    b->specs = specs;
    b->n_slots = (int)n;
    b->slots = cm_alloc(a, sizeof *b->slots * (n ? n : 1));
    const cm_aarg **given = cm_alloc(a, sizeof *given * (n ? n : 1));
    bool *guessed = cm_alloc(a, sizeof *guessed * (n ? n : 1)); /* a typo was reported for it */
    for (const cm_aarg *g = args; g; g = g->next) {
        size_t k = 0;
        while (k < n && strcmp(specs[k].name, g->name)) k++;
        if (k == n) {
            cm_suggest sg;
            cm_suggest_init(&sg, g->name);
            for (size_t j = 0; j < n; j++) cm_suggest_add(&sg, specs[j].name);
            char h[96];
            cm_error(cc->d, g->loc, "unknown parameter '%s' for '%s'%s", g->name, item, cm_suggest_hint(&sg, h, sizeof h));
            for (size_t j = 0; j < n; j++)
                if (sg.best == specs[j].name) guessed[j] = true;
            continue;
        }
        if (given[k]) {
            cm_error(cc->d, g->loc, "parameter '%s' of '%s' is given twice", g->name, item);
            continue;
        }
        given[k] = g;
    }
    for (size_t k = 0; k < n; k++) {
        const chasm_param_spec *s = &specs[k];
        const cm_aarg *g = given[k];
        cm_slot *out = &b->slots[k];
        const cm_unit *unit = cm_unit_find(s->unit ? s->unit : "");
        char what[256];
        snprintf(what, sizeof what, "parameter '%s' of '%s'", s->name, item);
        if (s->kind == CHASM_PARAM) {
            if (!g) {
                if (s->required && !guessed[k]) {
                    cm_error(cc->d, item_loc, "'%s' needs parameter '%s'%s%s", item, s->name, s->doc ? ": " : "",
                             s->doc ? s->doc : "");
                    continue;
                }
                out->d = s->def_number;
                out->i = (int64_t)s->def_number;
                out->b = s->def_number != 0;
                out->s = s->def_string ? s->def_string : "";
                continue;
            }
            if (g->val.kind == V_NAME) {
                cm_error(cc->d, g->val.loc, "%s takes a value, not the variable '%s'", what, g->val.str);
                continue;
            }
            if (cm_value(cc, &g->val, s->type, unit, what, out)) continue;
            out->given = true;
            if (s->type == CHASM_INT) out->d = (double)out->i;
            if (s->has_range && (s->type == CHASM_DOUBLE || s->type == CHASM_INT) && (out->d < s->min || out->d > s->max)) {
                cm_error(cc->d, g->val.loc, "%s is %g %s, outside its range [%g, %g] %s", what, out->d, unit->name, s->min,
                         s->max, unit->name);
            }
            continue;
        }
        /* a variable slot */
        const char *vname = NULL;
        cm_loc vloc = item_loc;
        if (g) {
            if (g->val.kind != V_NAME) {
                cm_error(cc->d, g->val.loc, "%s names the variable it %s: write a variable name", what,
                         slot_kind_name(s->kind));
                continue;
            }
            vname = g->val.str;
            vloc = g->val.loc;
        } else if (s->def_string && s->def_string[0]) {
            vname = s->def_string;
            if (!cm_map_get(&cc->m->var_map, vname)) {
                cm_error(cc->d, item_loc, "'%s' %s variable '%s' (its default for '%s'), which the plan does not declare: "
                         "declare it or bind '%s = VARIABLE'", item, slot_kind_name(s->kind), vname, s->name, s->name);
                continue;
            }
        } else {
            if (s->required && !guessed[k]) cm_error(cc->d, item_loc, "'%s' needs parameter '%s' (the variable it %s)", item, s->name,
                                      slot_kind_name(s->kind));
            continue;
        }
        cm_var *v = cm_find_var(cc, vname, vloc, what);
        if (!v) continue;
        if (v->type != s->type) {
            cm_error(cc->d, vloc, "%s must be a %s variable, but '%s' is %s", what, cm_type_name(s->type), v->name,
                     cm_type_name(v->type));
            continue;
        }
        if (v->unit->dim != unit->dim || v->unit->to_si != unit->to_si) {
            cm_error(cc->d, vloc, "%s expects a variable in '%s', but '%s' is declared in '%s'", what,
                     unit->name[0] ? unit->name : "no unit", v->name, v->unit->name[0] ? v->unit->name : "no unit");
            continue;
        }
        out->var = v;
        if (s->kind == CHASM_WRITES && record_writers)
            cm_add_writer(cc, v, vloc, cm_sprintf(cc->a, "'%s' in state '%s'", item, st ? st->path : "?"), st);
    }
    if (cc->d->len != before) return NULL;
    if (ver->check) check_limits(cc, b, item, args, item_loc, st);
    if (cc->d->len != before) return NULL;
    return b;
}
