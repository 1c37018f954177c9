/* The Loader: parse every file, resolve parameters, load the plugins the plan
 * names, compile and check everything; either a complete machine or NULL and
 * every error found. No half-valid machine is ever returned. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chasm/cm_compile.h"
#include "chasm/cm_overrides.h"
#include "chasm/cm_parser.h"

struct chasm_errors {
    char **lines;
    size_t n;
};

size_t chasm_errors_count(const chasm_errors *e) { return e ? e->n : 0; }
const char *chasm_errors_get(const chasm_errors *e, size_t i) { return e && i < e->n ? e->lines[i] : NULL; }
void chasm_errors_free(chasm_errors *e)
{
    if (!e) return;
    for (size_t i = 0; i < e->n; i++) free(e->lines[i]);
    free(e->lines);
    free(e);
}

static int cmp_param(const void *a, const void *b)
{
    const cm_aparam *x = *(cm_aparam *const *)a, *y = *(cm_aparam *const *)b;
    if (x->depth != y->depth) return x->depth < y->depth ? -1 : 1;
    if (x->loc.file_order != y->loc.file_order) return x->loc.file_order < y->loc.file_order ? -1 : 1;
    return x->loc.line < y->loc.line ? -1 : (x->loc.line > y->loc.line);
}

/* The outermost definition wins (command line, then the plan file, then the
 * files it includes): a vehicle file sets its values and includes a template. */
static void resolve_params(cm_cc *cc)
{
    size_t n = 0;
    for (cm_aparam *p = cc->plan->params; p; p = p->next) n++;
    if (!n) return;
    cm_aparam **v = malloc(n * sizeof *v);
    if (!v) abort();
    n = 0;
    for (cm_aparam *p = cc->plan->params; p; p = p->next) v[n++] = p;
    qsort(v, n, sizeof *v, cmp_param);
    for (size_t i = 0; i < n; i++) {
        cm_aparam *prev = cm_map_put(&cc->m->param_map, v[i]->name, v[i]);
        if (prev && prev->depth == v[i]->depth)
            cm_error(cc->d, v[i]->loc, "parameter '%s' is defined twice (first at %s:%d:%d)", v[i]->name, prev->loc.file,
                     prev->loc.line, prev->loc.col);
    }
    free(v);
}

static chasm_machine *load(const char *path, const char *name, const char *text, size_t len, const chasm_options *opt,
                           chasm_errors **errors)
{
    chasm_machine *m = calloc(1, sizeof *m);
    if (!m) abort();
    if (opt) m->opt = *opt;
    m->run = CHASM_RUN_LOADED;
    m->last_us = CM_NEVER;
    m->last_cond = "";
    cm_diag d = {0};
    d.limit = 500;
    cm_aplan *plan = cm_alloc(&m->arena, sizeof *plan);
    m->plan = plan;
    cm_parse_ctx pc = {.arena = &m->arena, .diag = &d, .plan = plan};
    /* Overrides are values, never plan text (cm_overrides.c). */
    for (size_t i = 0; opt && i < opt->n_params; i++)
        cm_parse_override(&pc, opt->param_names[i], opt->param_values[i]);
    if (path) {
        cm_parse_file(&pc, cm_strdup(&m->arena, path), NULL);
        m->plan_name = cm_strdup(&m->arena, path);
    } else if (len > CHASM_MAX_FILE_BYTES) {
        cm_error(&d, (cm_loc){cm_strdup(&m->arena, name), 0, 1, 1}, "plan text larger than %d bytes (CHASM_MAX_FILE_BYTES)",
                 CHASM_MAX_FILE_BYTES);
        m->plan_name = cm_strdup(&m->arena, name);
    } else {
        pc.stack[0] = name;
        pc.depth = 1;
        cm_parse_text(&pc, cm_strdup(&m->arena, name), opt && opt->base_dir ? opt->base_dir : "", text, len, NULL);
        pc.depth = 0;
        m->plan_name = cm_strdup(&m->arena, name);
    }
    m->n_lines = plan->n_lines;
    cm_check_overrides(&d, plan);
    cm_cc cc = {.m = m, .a = &m->arena, .d = &d, .plan = plan};
    if (!d.len) {
        resolve_params(&cc);
        cm_load_plugins(&cc);
        cm_compile_vars(&cc);
        cm_compile_states(&cc);
        cm_compile_tests(&cc);
        cm_compile_actions(&cc);
        cm_compile_transitions(&cc);
        cm_check_writers(&cc);
    }
    cm_map_free(&cc.path_map);
    cm_map_free(&cc.name_map);
    cm_map_free(&cc.test_map);
    cm_map_free(&cc.plugin_map);
    if (d.len) {
        cm_diag_sort(&d);
        if (errors) {
            chasm_errors *e = calloc(1, sizeof *e);
            if (!e) abort();
            e->lines = malloc(d.len * sizeof *e->lines);
            if (!e->lines) abort();
            for (size_t i = 0; i < d.len; i++) {
                e->lines[i] = d.items[i].text;
                d.items[i].text = NULL;
            }
            e->n = d.len;
            *errors = e;
        }
        cm_diag_free(&d);
        chasm_free(m);
        return NULL;
    }
    cm_diag_free(&d);
    if (errors) *errors = NULL;
    return m;
}

chasm_machine *chasm_load_file(const char *path, const chasm_options *opt, chasm_errors **errors)
{
    return load(path, NULL, NULL, 0, opt, errors);
}

chasm_machine *chasm_load_string(const char *name, const char *text, size_t len, const chasm_options *opt,
                                 chasm_errors **errors)
{
    return load(NULL, name ? name : "<string>", text, len, opt, errors);
}

void chasm_free(chasm_machine *m)
{
    if (!m) return;
    if (m->run == CHASM_RUN_RUNNING || m->run == CHASM_RUN_PAUSED) {
        /* stop behaviors so plugins can release what they hold */
        cm_stop_all(m);
    }
    cm_plugins_unload_all(m);
    cm_streams_free(m);
    cm_map_free(&m->var_map);
    cm_map_free(&m->param_map);
    cm_arena_free(&m->arena);
    free(m);
}

size_t chasm_state_count(const chasm_machine *m) { return (size_t)m->n_states; }
size_t chasm_test_count(const chasm_machine *m) { return m->n_tests_total; }
