/* Hot plug: a new code version of a plugin the running plan uses. Every use
 * is re-bound against the new schema first; only if all bind does anything
 * change. Inactive states switch at once, active ones keep the old code until
 * they are left (the runtime adopts the pending binding); the old version is
 * unloaded when nothing uses it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chasm/cm_compile.h"

void cm_binding_release(chasm_machine *m, cm_binding *b)
{
    if (!b) return;
    cm_plugin_version *v = b->ver;
    if (--v->refs == 0 && v->retired) {
        cm_log(m, "", "plugin '%s' version %d (%s) unloaded", v->plugin->name, v->serial, v->desc->version);
        cm_plugin_version_unload(m, v);
    }
}

void cm_binding_adopt_pending(chasm_machine *m, cm_binding **cur, cm_binding **pending)
{
    if (!*pending) return;
    cm_binding_release(m, *cur);
    *cur = *pending;
    *pending = NULL;
}

static bool state_active(const chasm_machine *m, const cm_state *s)
{
    return m->run == CHASM_RUN_RUNNING || m->run == CHASM_RUN_PAUSED
               ? (s->depth < m->path_len && m->path[s->depth] == s)
               : false;
}

/* Commits a new binding nb of one use: an active state keeps its code and
 * takes nb at its next entry (pending, adopted by the runtime); any other
 * switches now. A binding replaced here is released (and its version
 * unloaded if that was its last use). */
static void install(chasm_machine *m, cm_binding **cur, cm_binding **pending, cm_binding *nb, bool active)
{
    if (!nb) return;
    nb->ver->refs++;
    cm_binding_release(m, *pending);
    *pending = NULL;
    if (active) {
        *pending = nb;
        return;
    }
    cm_binding *o = *cur;
    *cur = nb;
    cm_binding_release(m, o);
}

static void join_errors(cm_diag *d, char *err, size_t el)
{
    err[0] = 0;
    for (size_t i = 0; i < d->len && strlen(err) + 2 < el; i++)
        snprintf(err + strlen(err), el - strlen(err), "%s%s", i ? "\n" : "", d->items[i].text);
}

/* A new binding of one action against version v of its plugin p (NULL if it
 * does not bind; the reasons are in cc->d). */
static cm_binding *bind_action(cm_cc *cc, cm_plugin *p, cm_plugin_version *v, cm_action *a, cm_state *s)
{
    const void *spec = NULL;
    if (cm_find_plugin_of(cc, a->ast->behavior, 0, a->ast->beh_loc, &spec) != p) return NULL;
    const chasm_behavior_spec *bs = spec;
    cm_binding *nb = cm_bind(cc, &v->arena, v, a->text, bs->params, bs->n_params, a->ast->args, a->loc, s, false);
    if (!nb) return NULL;
    nb->beh = bs;
    nb->inst_size = bs->state_size;
    nb->inst = bs->state_size ? cm_alloc(&v->arena, bs->state_size) : NULL;
    /* the one-writer rule was checked for the old version's variables */
    for (int j = 0; j < nb->n_slots; j++) {
        if (nb->specs[j].kind != CHASM_WRITES || !nb->slots[j].var) continue;
        int ok = 0;
        for (int o = 0; o < a->cur->n_slots; o++)
            ok |= a->cur->specs[o].kind == CHASM_WRITES && a->cur->slots[o].var == nb->slots[j].var;
        if (!ok)
            cm_error(cc->d, a->loc, "the new version of '%s' writes '%s', which the running plan did not check", a->text,
                     nb->slots[j].var->name);
    }
    return nb;
}

/* The same for a test handler (s is NULL for a global test). */
static cm_binding *bind_test(cm_cc *cc, cm_plugin *p, cm_plugin_version *v, cm_test *t, cm_state *s)
{
    const void *spec = NULL;
    if (cm_find_plugin_of(cc, t->ast->crit.handler, 1, t->ast->crit.var_loc, &spec) != p) return NULL;
    const chasm_test_spec *ts = spec;
    cm_binding *nb = cm_bind(cc, &v->arena, v, t->ast->crit.handler, ts->params, ts->n_params, t->ast->crit.args, t->loc,
                             s, false);
    if (nb) nb->test = ts;
    return nb;
}

static bool is_use_of(const cm_binding *b, const cm_plugin *p) { return b && b->ver->plugin == p; }

/* Binds every use of plugin p against its version v; the new bindings wait
 * in pending_new until all are known to bind. Returns how many. */
static int bind_uses(chasm_machine *m, cm_cc *cc, cm_plugin *p, cm_plugin_version *v)
{
    int n = 0;
    for (int i = 0; i < m->n_states; i++) {
        cm_state *s = &m->states[i];
        for (int k = 0; k < s->n_actions; k++) {
            cm_action *a = &s->actions[k];
            if (a->kind == ACT_PLUGIN && is_use_of(a->cur, p)) n += (a->pending_new = bind_action(cc, p, v, a, s)) != NULL;
        }
        for (int k = 0; k < s->n_tests; k++) {
            cm_test *t = &s->tests[k];
            if (t->kind == CR_HANDLER && is_use_of(t->cur, p)) n += (t->pending_new = bind_test(cc, p, v, t, s)) != NULL;
        }
    }
    for (int k = 0; k < m->n_globals; k++) {
        cm_test *t = &m->globals[k];
        if (t->kind == CR_HANDLER && is_use_of(t->cur, p)) n += (t->pending_new = bind_test(cc, p, v, t, NULL)) != NULL;
    }
    return n;
}

/* commit: every use takes its new binding (global tests, evaluated all the
 * time, at once); !commit: the new bindings are forgotten (they live in the
 * new version's arena, which goes with it). */
static void finish_uses(chasm_machine *m, bool commit)
{
    for (int i = 0; i < m->n_states; i++) {
        cm_state *s = &m->states[i];
        for (int k = 0; k < s->n_actions; k++) {
            cm_action *a = &s->actions[k];
            if (commit) install(m, &a->cur, &a->pending, a->pending_new, state_active(m, s));
            a->pending_new = NULL;
        }
        for (int k = 0; k < s->n_tests; k++) {
            cm_test *t = &s->tests[k];
            if (commit) install(m, &t->cur, &t->pending, t->pending_new, state_active(m, s));
            t->pending_new = NULL;
        }
    }
    for (int k = 0; k < m->n_globals; k++) {
        cm_test *t = &m->globals[k];
        if (commit) install(m, &t->cur, &t->pending, t->pending_new, false);
        t->pending_new = NULL;
    }
}

int chasm_hotplug(chasm_machine *m, const char *path, char *err, size_t el)
{
    char tmp[1024];
    if (!err) {
        err = tmp;
        el = sizeof tmp;
    }
    cm_plugin_version *v = cm_plugin_version_open(m, path, err, el);
    if (!v) return -1;
    cm_plugin *p = NULL;
    for (int i = 0; i < m->n_plugins; i++)
        if (!strcmp(m->plugins[i].name, v->desc->name)) p = &m->plugins[i];
    if (!p) {
        snprintf(err, el, "plugin '%s' (from '%s') is not used by the running plan: nothing to update", v->desc->name, path);
        cm_plugin_version_unload(m, v);
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
    cm_plugin_version *old = p->current;
    p->current = v; /* lookups must see the new descriptor */
    int n_items = bind_uses(m, &cc, p, v);
    finish_uses(m, d.len == 0);
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
        cm_plugin_version_unload(m, v);
        return -1;
    }
    cm_diag_free(&d);
    p->n_versions++;
    old->retired = true;
    cm_log(m, "", "plugin '%s' version %d (%s) loaded from '%s' for %d uses", p->name, v->serial, v->desc->version, path,
           n_items);
    if (old->refs == 0) cm_plugin_version_unload(m, old);
    return 0;
}
