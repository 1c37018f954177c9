/* Plugins: find the file on the search path, copy it to a private unique path
 * (dlopen returns the same handle for a path it already has open, so every
 * version gets its own copy), dlopen, check the one exported descriptor, and
 * bind plan arguments against each behavior's parameter schema. */
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "chasm/cm_compile.h"

char *mkdtemp(char *);

static int copy_file(const char *src, const char *dst)
{
    int in = open(src, O_RDONLY);
    if (in < 0) return -1;
    int out = open(dst, O_WRONLY | O_CREAT | O_EXCL, 0700);
    if (out < 0) {
        close(in);
        return -1;
    }
    char buf[65536];
    ssize_t r;
    int rc = 0;
    while ((r = read(in, buf, sizeof buf)) > 0)
        if (write(out, buf, (size_t)r) != r) {
            rc = -1;
            break;
        }
    if (r < 0) rc = -1;
    close(in);
    if (close(out)) rc = -1;
    return rc;
}

static int valid_spec_list(const chasm_param_spec *p, size_t n, int is_test, char *err, size_t el, const char *what)
{
    if (n > 64 || (n && !p)) {
        snprintf(err, el, "%s: bad parameter table (%zu entries)", what, n);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        if (!p[i].name || !p[i].name[0]) {
            snprintf(err, el, "%s: parameter %zu has no name", what, i);
            return -1;
        }
        if ((unsigned)p[i].type > CHASM_STRING || (unsigned)p[i].kind > CHASM_WRITES) {
            snprintf(err, el, "%s: parameter '%s' has an unknown type or kind", what, p[i].name);
            return -1;
        }
        if (is_test && p[i].kind == CHASM_WRITES) {
            snprintf(err, el, "%s: test handlers may not write variables ('%s')", what, p[i].name);
            return -1;
        }
        const cm_unit *u = cm_unit_find(p[i].unit ? p[i].unit : "");
        if (!u || (u->dim != CM_DIM_NONE && p[i].type != CHASM_DOUBLE)) {
            snprintf(err, el, "%s: parameter '%s' has an unknown or misplaced unit '%s'", what, p[i].name,
                     p[i].unit ? p[i].unit : "");
            return -1;
        }
        for (size_t j = 0; j < i; j++)
            if (!strcmp(p[j].name, p[i].name)) {
                snprintf(err, el, "%s: parameter '%s' is listed twice", what, p[i].name);
                return -1;
            }
    }
    return 0;
}

static int valid_descriptor(const chasm_plugin_descriptor *d, const char *path, char *err, size_t el)
{
    if (d->abi_version != CHASM_PLUGIN_ABI || d->struct_size != sizeof *d) {
        snprintf(err, el, "'%s' was built for plugin ABI %u, this CHASM uses ABI %d: rebuild it against chasm_plugin.h",
                 path, d->abi_version, CHASM_PLUGIN_ABI);
        return -1;
    }
    if (!d->name || !d->name[0] || !d->version || d->n_behaviors > 1024 || d->n_tests > 1024 ||
        (d->n_behaviors && !d->behaviors) || (d->n_tests && !d->tests)) {
        snprintf(err, el, "'%s' has an invalid descriptor (name, version or tables missing)", path);
        return -1;
    }
    char what[256];
    for (size_t i = 0; i < d->n_behaviors; i++) {
        const chasm_behavior_spec *b = &d->behaviors[i];
        if (!b->name || !b->step) {
            snprintf(err, el, "plugin '%s': behavior %zu has no name or no step function", d->name, i);
            return -1;
        }
        snprintf(what, sizeof what, "plugin '%s': behavior '%s'", d->name, b->name);
        if (valid_spec_list(b->params, b->n_params, 0, err, el, what)) return -1;
    }
    for (size_t i = 0; i < d->n_tests; i++) {
        const chasm_test_spec *t = &d->tests[i];
        if (!t->name || !t->evaluate) {
            snprintf(err, el, "plugin '%s': test handler %zu has no name or no evaluate function", d->name, i);
            return -1;
        }
        snprintf(what, sizeof what, "plugin '%s': test handler '%s'", d->name, t->name);
        if (valid_spec_list(t->params, t->n_params, 1, err, el, what)) return -1;
    }
    return 0;
}

static void unload_version(chasm_machine *m, cm_plugin_version *v)
{
    for (cm_plugin_version **pp = &m->loaded; *pp; pp = &(*pp)->next_loaded)
        if (*pp == v) {
            *pp = v->next_loaded;
            break;
        }
    if (v->dl) dlclose(v->dl);
    cm_arena_free(&v->arena);
    free(v);
}

/* Opens one file as a new code version; NULL with err set on any problem. */
static cm_plugin_version *open_version(chasm_machine *m, const char *path, char *err, size_t el)
{
    if (!m->tmpdir[0]) {
        const char *t = getenv("TMPDIR");
        snprintf(m->tmpdir, sizeof m->tmpdir, "%s/chasm-plugins-XXXXXX", t && t[0] ? t : "/tmp");
        if (!mkdtemp(m->tmpdir)) {
            snprintf(err, el, "cannot create a folder for plugin copies: %s", strerror(errno));
            m->tmpdir[0] = 0;
            return NULL;
        }
    }
    char copy[512];
    snprintf(copy, sizeof copy, "%s/v%d.so", m->tmpdir, ++m->copy_counter);
    if (copy_file(path, copy)) {
        snprintf(err, el, "cannot read plugin file '%s': %s", path, strerror(errno));
        unlink(copy);
        return NULL;
    }
    dlerror();
    void *dl = dlopen(copy, RTLD_NOW | RTLD_LOCAL);
    unlink(copy); /* the mapping stays; nothing is left on disk */
    if (!dl) {
        const char *e = dlerror();
        const char *colon = e ? strstr(e, ".so: ") : NULL;
        snprintf(err, el, "cannot load plugin file '%s': %s", path, colon ? colon + 5 : e ? e : "dlopen failed");
        return NULL;
    }
    const chasm_plugin_descriptor *d = dlsym(dl, CHASM_PLUGIN_SYMBOL);
    if (!d) {
        snprintf(err, el, "'%s' does not export the symbol '%s' (is it a CHASM plugin? see chasm_plugin.h)", path,
                 CHASM_PLUGIN_SYMBOL);
        dlclose(dl);
        return NULL;
    }
    if (valid_descriptor(d, path, err, el)) {
        dlclose(dl);
        return NULL;
    }
    cm_plugin_version *v = calloc(1, sizeof *v);
    if (!v) abort();
    v->dl = dl;
    v->desc = d;
    v->next_loaded = m->loaded;
    m->loaded = v;
    return v;
}

static const char *find_file(cm_cc *cc, const char *name)
{
    const chasm_options *o = &cc->m->opt;
    for (size_t i = 0; i < o->n_plugin_path; i++) {
        const char *forms[] = {"%s/chasm_%s.so", "%s/%s.so"};
        for (int f = 0; f < 2; f++) {
            char *p = cm_sprintf(cc->a, forms[f], o->plugin_path[i], name);
            if (access(p, R_OK) == 0) return p;
        }
    }
    return NULL;
}

void cm_load_plugins(cm_cc *cc)
{
    chasm_machine *m = cc->m;
    int n = 0;
    for (cm_ause *u = cc->plan->uses; u; u = u->next) n++;
    m->plugins = cm_alloc(cc->a, sizeof *m->plugins * (size_t)(n ? n : 1));
    for (cm_ause *u = cc->plan->uses; u; u = u->next) {
        if (cm_map_get(&cc->plugin_map, u->name)) continue; /* `use` twice is harmless */
        const char *file = find_file(cc, u->name);
        if (!file) {
            char dirs[1024] = "";
            for (size_t i = 0; i < m->opt.n_plugin_path; i++)
                snprintf(dirs + strlen(dirs), sizeof dirs - strlen(dirs), "%s%s", i ? ", " : "", m->opt.plugin_path[i]);
            if (m->opt.n_plugin_path)
                cm_error(cc->d, u->loc, "plugin '%s' not found: no chasm_%s.so or %s.so in the plugin path (%s)", u->name,
                         u->name, u->name, dirs);
            else
                cm_error(cc->d, u->loc, "plugin '%s' not found: the plugin path is empty (use --plugin-path DIR or "
                         "CHASM_PLUGIN_PATH)", u->name);
            continue;
        }
        char err[1024];
        cm_plugin_version *v = open_version(m, file, err, sizeof err);
        if (!v) {
            cm_error(cc->d, u->loc, "plugin '%s': %s", u->name, err);
            continue;
        }
        if (strcmp(v->desc->name, u->name)) {
            cm_error(cc->d, u->loc, "plugin file '%s' holds plugin '%s', not '%s'", file, v->desc->name, u->name);
            unload_version(m, v);
            continue;
        }
        cm_plugin *p = &m->plugins[m->n_plugins++];
        p->name = u->name;
        p->file = file;
        p->loc = u->loc;
        p->current = v;
        p->n_versions = 1;
        v->plugin = p;
        v->serial = 1;
        cm_map_put(&cc->plugin_map, p->name, p);
    }
}

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
    else if (!m->n_plugins && !want_test)
        cm_error(cc->d, loc, "unknown behavior '%s' (the plan uses no plugins: add `use PLUGIN`; the built-in action is `set`)", item);
    else cm_error(cc->d, loc, "unknown %s '%s' (not in any plugin named by `use`)", kind, item);
    return NULL;
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
    return b;
}

/* ------------------------------------------------------------ hot plug */

void cm_binding_release(chasm_machine *m, cm_binding *b)
{
    if (!b) return;
    cm_plugin_version *v = b->ver;
    if (--v->refs == 0 && v->retired) {
        cm_log(m, "", "plugin '%s' version %d (%s) unloaded", v->plugin->name, v->serial, v->desc->version);
        unload_version(m, v);
    }
}

static bool state_active(const chasm_machine *m, const cm_state *s)
{
    return m->run == CHASM_RUN_RUNNING || m->run == CHASM_RUN_PAUSED
               ? (s->depth < m->path_len && m->path[s->depth] == s)
               : false;
}

static void join_errors(cm_diag *d, char *err, size_t el)
{
    err[0] = 0;
    for (size_t i = 0; i < d->len && strlen(err) + 2 < el; i++)
        snprintf(err + strlen(err), el - strlen(err), "%s%s", i ? "\n" : "", d->items[i].text);
}

int chasm_hotplug(chasm_machine *m, const char *path, char *err, size_t el)
{
    char tmp[1024];
    if (!err) {
        err = tmp;
        el = sizeof tmp;
    }
    cm_plugin_version *v = open_version(m, path, err, el);
    if (!v) return -1;
    cm_plugin *p = NULL;
    for (int i = 0; i < m->n_plugins; i++)
        if (!strcmp(m->plugins[i].name, v->desc->name)) p = &m->plugins[i];
    if (!p) {
        snprintf(err, el, "plugin '%s' (from '%s') is not used by the running plan: nothing to update", v->desc->name, path);
        unload_version(m, v);
        return -1;
    }
    v->plugin = p;
    v->serial = p->n_versions + 1;
    cm_diag d = {0};
    d.limit = 20;
    cm_cc cc = {0};
    cc.m = m;
    cc.a = &v->arena;
    cc.d = &d;
    cc.plan = m->plan;
    cm_plugin *saved = p->current->plugin; /* lookups must see the new descriptor */
    (void)saved;
    cm_plugin_version *old = p->current;
    p->current = v;
    int n_items = 0;
    for (int pass = 0; pass < 2 && !d.len; pass++) {
        /* pass 0 binds everything and checks; pass 1 commits. */
        for (int i = 0; i < m->n_states; i++) {
            cm_state *s = &m->states[i];
            for (int k = 0; k < s->n_actions; k++) {
                cm_action *a = &s->actions[k];
                if (a->kind != ACT_PLUGIN || a->cur->ver->plugin != p) continue;
                if (pass == 0) {
                    const void *spec = NULL;
                    cm_plugin *q = cm_find_plugin_of(&cc, a->ast->behavior, 0, a->ast->beh_loc, &spec);
                    if (q != p) continue;
                    const chasm_behavior_spec *bs = spec;
                    cm_binding *nb = cm_bind(&cc, &v->arena, v, a->text, bs->params, bs->n_params, a->ast->args, a->loc, s, false);
                    if (!nb) continue;
                    nb->beh = bs;
                    nb->inst_size = bs->state_size;
                    nb->inst = bs->state_size ? cm_alloc(&v->arena, bs->state_size) : NULL;
                    /* the one-writer rule was checked for the old version's variables */
                    for (int j = 0; j < nb->n_slots; j++) {
                        if (nb->specs[j].kind != CHASM_WRITES || !nb->slots[j].var) continue;
                        int ok = 0;
                        for (int o = 0; o < a->cur->n_slots; o++)
                            ok |= a->cur->specs[o].kind == CHASM_WRITES && a->cur->slots[o].var == nb->slots[j].var;
                        if (!ok) cm_error(&d, a->loc, "the new version of '%s' writes '%s', which the running plan did not check",
                                          a->text, nb->slots[j].var->name);
                    }
                    a->pending_new = nb;
                    n_items++;
                } else {
                    cm_binding *nb = a->pending_new;
                    a->pending_new = NULL;
                    if (!nb) continue;
                    nb->ver->refs++;
                    if (state_active(m, s)) {
                        cm_binding_release(m, a->pending);
                        a->pending = nb;
                    } else {
                        cm_binding *o = a->cur;
                        a->cur = nb;
                        if (a->pending) {
                            cm_binding_release(m, a->pending);
                            a->pending = NULL;
                        }
                        cm_binding_release(m, o);
                    }
                }
            }
            for (int k = 0; k < s->n_tests; k++) {
                cm_test *t = &s->tests[k];
                if (t->kind != CR_HANDLER || t->cur->ver->plugin != p) continue;
                if (pass == 0) {
                    const void *spec = NULL;
                    if (cm_find_plugin_of(&cc, t->ast->crit.handler, 1, t->ast->crit.var_loc, &spec) != p) continue;
                    const chasm_test_spec *ts = spec;
                    cm_binding *nb = cm_bind(&cc, &v->arena, v, t->ast->crit.handler, ts->params, ts->n_params,
                                             t->ast->crit.args, t->loc, s, false);
                    if (nb) nb->test = ts;
                    t->pending_new = nb;
                    n_items++;
                } else {
                    cm_binding *nb = t->pending_new;
                    t->pending_new = NULL;
                    if (!nb) continue;
                    nb->ver->refs++;
                    if (state_active(m, s)) {
                        cm_binding_release(m, t->pending);
                        t->pending = nb;
                    } else {
                        cm_binding *o = t->cur;
                        t->cur = nb;
                        if (t->pending) {
                            cm_binding_release(m, t->pending);
                            t->pending = NULL;
                        }
                        cm_binding_release(m, o);
                    }
                }
            }
        }
        if (pass == 0) {
            /* global test handlers are evaluated all the time: they switch at once */
            for (int k = 0; k < m->n_globals; k++) {
                cm_test *t = &m->globals[k];
                if (t->kind != CR_HANDLER || t->cur->ver->plugin != p) continue;
                const void *spec = NULL;
                if (cm_find_plugin_of(&cc, t->ast->crit.handler, 1, t->ast->crit.var_loc, &spec) != p) continue;
                const chasm_test_spec *ts = spec;
                cm_binding *nb = cm_bind(&cc, &v->arena, v, t->ast->crit.handler, ts->params, ts->n_params, t->ast->crit.args, t->loc, NULL, false);
                if (nb) nb->test = ts;
                t->pending_new = nb;
            }
        } else {
            for (int k = 0; k < m->n_globals; k++) {
                cm_test *t = &m->globals[k];
                cm_binding *nb = t->pending_new;
                t->pending_new = NULL;
                if (!nb) continue;
                nb->ver->refs++;
                cm_binding *o = t->cur;
                t->cur = nb;
                cm_binding_release(m, o);
            }
        }
        if (pass == 0 && d.len) {
            /* roll back: forget the new bindings, keep the old code */
            for (int i = 0; i < m->n_states; i++) {
                for (int k = 0; k < m->states[i].n_actions; k++) m->states[i].actions[k].pending_new = NULL;
                for (int k = 0; k < m->states[i].n_tests; k++) m->states[i].tests[k].pending_new = NULL;
            }
            for (int k = 0; k < m->n_globals; k++) m->globals[k].pending_new = NULL;
        }
    }
    if (d.len) {
        cm_diag_sort(&d);
        char head[256];
        snprintf(head, sizeof head, "new version of plugin '%s' rejected, the mission keeps version %d:\n", p->name,
                 old->serial);
        char body[2048];
        join_errors(&d, body, sizeof body);
        snprintf(err, el, "%s%s", head, body);
        cm_diag_free(&d);
        p->current = old;
        unload_version(m, v);
        return -1;
    }
    cm_diag_free(&d);
    p->n_versions++;
    old->retired = true;
    cm_log(m, "", "plugin '%s' version %d (%s) loaded from '%s' for %d uses", p->name, v->serial, v->desc->version, path,
           n_items);
    if (old->refs == 0) unload_version(m, old);
    return 0;
}

int chasm_plugin_versions_loaded(const chasm_machine *m)
{
    int n = 0;
    for (cm_plugin_version *v = m->loaded; v; v = v->next_loaded) n++;
    return n;
}

void cm_plugins_unload_all(chasm_machine *m)
{
    while (m->loaded) unload_version(m, m->loaded);
    if (m->tmpdir[0]) rmdir(m->tmpdir);
}
