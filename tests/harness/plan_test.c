/* Plan-test helpers (plan_test.h). */
#include "plan_test.h"

char pt_log[65536];

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
    const char *dirs[] = {unit_plugin_dir};
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
    if (!m)
        unit_fail(NULL, 0, "the plan did not load");
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

const char *pt_first_error(const char *plan)
{
    static char first[4096];
    snprintf(first, sizeof first, "%s", pt_errors(plan));
    first[strcspn(first, "\n")] = '\0';
    return first;
}

static int var(chasm_machine *m, const char *name)
{
    int id = chasm_var_find(m, name);
    if (id < 0)
        unit_fail(NULL, 0, "no variable '%s'", name);
    return id;
}

static int64_t us(double t_s) { return (int64_t)llround(t_s * 1e6); }

/* A set the engine refused (wrong type, out of range, an output) is a failure. */
static void set_done(int rc, const char *name)
{
    if (rc)
        unit_fail(NULL, 0, "cannot set %s", name);
}

void pt_set(chasm_machine *m, const char *name, double v, double t_s)
{
    set_done(chasm_var_set_double(m, var(m, name), v, us(t_s)), name);
}

void pt_set_bool(chasm_machine *m, const char *name, int v, double t_s)
{
    set_done(chasm_var_set_bool(m, var(m, name), v, us(t_s)), name);
}

void pt_set_int(chasm_machine *m, const char *name, long v, double t_s)
{
    set_done(chasm_var_set_int(m, var(m, name), v, us(t_s)), name);
}

double pt_get(chasm_machine *m, const char *name) { return chasm_var_get_double(m, var(m, name)); }

int64_t pt_get_int(chasm_machine *m, const char *name) { return chasm_var_get_int(m, var(m, name)); }

void pt_start(chasm_machine *m, double t_s) { chasm_start(m, us(t_s)); }

chasm_run_state pt_step(chasm_machine *m, double t_s) { return chasm_step(m, us(t_s)); }

chasm_run_state pt_run_until(chasm_machine *m, double t0_s, double t1_s)
{
    for (int64_t t = us(t0_s); t <= us(t1_s); t += 100000)
        if (chasm_step(m, t) != CHASM_RUN_RUNNING)
            break;
    return chasm_run_state_of(m);
}

const char *pt_leaf(chasm_machine *m)
{
    static chasm_status st;
    chasm_status_get(m, 0, &st);
    return st.leaf_path;
}
