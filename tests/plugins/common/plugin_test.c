#include "plugin_test.h"

#include <stdlib.h>

int pt_failures;
char pt_log[8192];
static const char *plugin_dir = ".";

static void on_log(void *user, int64_t now, const char *path, const char *msg)
{
    (void)user;
    (void)now;
    (void)path;
    size_t n = strlen(pt_log);
    snprintf(pt_log + n, sizeof pt_log - n, "%s;", msg);
}

void pt_log_clear(void) { pt_log[0] = '\0'; }

static chasm_machine *load(const char *plan, chasm_errors **errs)
{
    const char *dirs[] = {plugin_dir};
    chasm_options o = {0};
    o.plugin_path = dirs;
    o.n_plugin_path = 1;
    o.log = on_log;
    return chasm_load_string("t.chasm", plan, strlen(plan), &o, errs);
}

chasm_machine *pt_load(const char *plan)
{
    chasm_errors *e = NULL;
    chasm_machine *m = load(plan, &e);
    for (size_t i = 0; i < chasm_errors_count(e); i++)
        fprintf(stderr, "%s\n", chasm_errors_get(e, i));
    chasm_errors_free(e);
    if (!m) {
        fprintf(stderr, "the plan did not load\n");
        pt_failures++;
    }
    return m;
}

const char *pt_errors(const char *plan)
{
    static char buf[4096];
    chasm_errors *e = NULL;
    chasm_machine *m = load(plan, &e);
    buf[0] = '\0';
    for (size_t i = 0; i < chasm_errors_count(e); i++) {
        size_t n = strlen(buf);
        snprintf(buf + n, sizeof buf - n, "%s\n", chasm_errors_get(e, i));
    }
    chasm_errors_free(e);
    chasm_free(m);
    return buf;
}

static int var(chasm_machine *m, const char *name)
{
    int id = chasm_var_find(m, name);
    if (id < 0) {
        fprintf(stderr, "no variable '%s'\n", name);
        pt_failures++;
    }
    return id;
}

static int64_t us(double t_s) { return (int64_t)llround(t_s * 1e6); }

void pt_set(chasm_machine *m, const char *name, double v, double t_s)
{
    chasm_var_set_double(m, var(m, name), v, us(t_s));
}

void pt_set_int(chasm_machine *m, const char *name, long v, double t_s)
{
    chasm_var_set_int(m, var(m, name), v, us(t_s));
}

double pt_get(chasm_machine *m, const char *name) { return chasm_var_get_double(m, var(m, name)); }

void pt_start(chasm_machine *m, double t_s) { chasm_start(m, us(t_s)); }

chasm_run_state pt_step(chasm_machine *m, double t_s) { return chasm_step(m, us(t_s)); }

const char *pt_leaf(chasm_machine *m)
{
    static chasm_status st;
    chasm_status_get(m, 0, &st);
    return st.leaf_path;
}

int main(int argc, char **argv)
{
    const char *only = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--plugins") && i + 1 < argc)
            plugin_dir = argv[++i];
        else
            only = argv[i];
    }
    int ran = 0, failed = 0;
    for (size_t i = 0; i < plugin_tests_count; i++) {
        if (only && strcmp(only, plugin_tests[i].name))
            continue;
        ran++;
        pt_failures = 0;
        pt_log_clear();
        plugin_tests[i].fn();
        if (pt_failures) {
            printf("FAIL %s (%d checks)\n", plugin_tests[i].name, pt_failures);
            failed++;
        } else {
            printf("ok %s\n", plugin_tests[i].name);
        }
    }
    if (!ran) {
        fprintf(stderr, "no test named '%s'\n", only ? only : "");
        return 2;
    }
    return failed ? 1 : 0;
}
