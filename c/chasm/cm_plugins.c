/* Plugins of a plan: find each `use`d file on the search path and open it
 * through cm_plugin_file.c (read, ELF check, private copy, probe, dlopen,
 * descriptor check) as a code version; unload versions. Binding plan
 * arguments is cm_plugin_bind.c, hot plug cm_hotplug.c. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "chasm/cm_compile.h"
#include "chasm/cm_plugin_file.h"

void cm_plugin_version_unload(chasm_machine *m, cm_plugin_version *v)
{
    for (cm_plugin_version **pp = &m->loaded; *pp; pp = &(*pp)->next_loaded)
        if (*pp == v) {
            *pp = v->next_loaded;
            break;
        }
    cm_plugin_code c = {v->dl, v->desc, v->check};
    cm_plugin_code_close(&c);
    cm_arena_free(&v->arena);
    free(v);
}

/* Opens one file as a new code version; NULL with err set on any problem. */
cm_plugin_version *cm_plugin_version_open(chasm_machine *m, const char *path, char *err, size_t el)
{
    cm_plugin_code c;
    if (cm_plugin_code_open(path, &c, err, el)) return NULL;
    cm_plugin_version *v = calloc(1, sizeof *v);
    if (!v) abort();
    v->dl = c.dl;
    v->desc = c.desc;
    v->check = c.check;
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
            /* anything by that name is the plugin: a directory, a dangling
             * link or an unreadable file is an error that names it, not a
             * reason to look further */
            struct stat st;
            if (lstat(p, &st) == 0) return p;
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
        char why[256];
        if (chasm_plugin_name_check(u->name, why, sizeof why)) {
            cm_error(cc->d, u->loc, "%s", why);
            continue;
        }
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
        cm_plugin_version *v = cm_plugin_version_open(m, file, err, sizeof err);
        if (!v) {
            /* the descriptor's checks name the plugin already ("plugin 'x': behavior ...") */
            char named[160];
            snprintf(named, sizeof named, "plugin '%s'", u->name);
            if (!strncmp(err, named, strlen(named)))
                cm_error(cc->d, u->loc, "%s", err);
            else
                cm_error(cc->d, u->loc, "%s: %s", named, err);
            continue;
        }
        if (strcmp(v->desc->name, u->name)) {
            cm_error(cc->d, u->loc, "plugin file '%s' holds plugin '%s', not '%s'", file, v->desc->name, u->name);
            cm_plugin_version_unload(m, v);
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

int chasm_plugin_versions_loaded(const chasm_machine *m)
{
    int n = 0;
    for (cm_plugin_version *v = m->loaded; v; v = v->next_loaded) n++;
    return n;
}

void cm_plugins_unload_all(chasm_machine *m)
{
    while (m->loaded) cm_plugin_version_unload(m, m->loaded);
}

int chasm_uses_plugin(const chasm_machine *m, const char *name)
{
    for (int i = 0; i < m->n_plugins; i++)
        if (!strcmp(m->plugins[i].name, name)) return 1;
    return 0;
}
