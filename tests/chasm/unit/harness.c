#include "harness.h"

#include <stdlib.h>

const char *plugin_dir = ".";
long alloc_count;

/* Linked with --wrap: every malloc/calloc/realloc of libchasm and the tests
 * passes here, so a test can check that stepping allocates nothing. */
void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t k);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t k);
void *__wrap_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n) { alloc_count++; return __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t k) { alloc_count++; return __real_calloc(n, k); }
void *__wrap_realloc(void *p, size_t n) { alloc_count++; return __real_realloc(p, n); }
int failures;
char logbuf[65536];

static void on_log(void *user, int64_t now, const char *path, const char *msg)
{
    (void)user;
    (void)now;
    (void)path;
    size_t L = strlen(logbuf);
    snprintf(logbuf + L, sizeof logbuf - L, "%s;", msg);
}

void log_clear(void) { logbuf[0] = 0; }

static chasm_machine *load_errors(const char *text, chasm_errors **e)
{
    const char *dirs[] = {plugin_dir};
    chasm_options o = {0};
    o.plugin_path = dirs;
    o.n_plugin_path = 1;
    o.log = on_log;
    return chasm_load_string("t.chasm", text, strlen(text), &o, e);
}

chasm_machine *load_plan(const char *text)
{
    chasm_errors *e = NULL;
    chasm_machine *m = load_errors(text, &e);
    for (size_t i = 0; i < chasm_errors_count(e); i++) fprintf(stderr, "%s\n", chasm_errors_get(e, i));
    chasm_errors_free(e);
    if (!m) {
        failures++;
        fprintf(stderr, "plan did not load\n");
    }
    return m;
}

const char *first_error(const char *text)
{
    static char buf[1024];
    chasm_errors *e = NULL;
    chasm_machine *m = load_errors(text, &e);
    snprintf(buf, sizeof buf, "%s", chasm_errors_count(e) ? chasm_errors_get(e, 0) : "");
    chasm_errors_free(e);
    chasm_free(m);
    return buf;
}

const char *leaf(chasm_machine *m)
{
    static chasm_status st;
    chasm_status_get(m, 0, &st);
    return st.leaf_path;
}

chasm_run_state run_until(chasm_machine *m, double t0, double t1)
{
    for (int64_t t = (int64_t)(t0 * 1e6 + 0.5); t <= (int64_t)(t1 * 1e6 + 0.5); t += 100000)
        if (chasm_step(m, t) != CHASM_RUN_RUNNING) break;
    return chasm_run_state_of(m);
}

void set_d(chasm_machine *m, const char *var, double v, double t)
{
    if (chasm_var_set_double(m, chasm_var_find(m, var), v, (int64_t)(t * 1e6))) {
        fprintf(stderr, "cannot set %s\n", var);
        failures++;
    }
}

void set_b(chasm_machine *m, const char *var, int v, double t)
{
    if (chasm_var_set_bool(m, chasm_var_find(m, var), v, (int64_t)(t * 1e6))) {
        fprintf(stderr, "cannot set %s\n", var);
        failures++;
    }
}

double get_d(chasm_machine *m, const char *var) { return chasm_var_get_double(m, chasm_var_find(m, var)); }
int64_t get_i(chasm_machine *m, const char *var) { return chasm_var_get_int(m, chasm_var_find(m, var)); }

extern const unit_test semantics_tests[], plugin_tests[], stream_tests[];

int main(int argc, char **argv)
{
    const char *only = NULL;
    int list = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--plugins") && i + 1 < argc) plugin_dir = argv[++i];
        else if (!strcmp(argv[i], "--list")) list = 1;
        else only = argv[i];
    }
    const unit_test *groups[] = {semantics_tests, plugin_tests, stream_tests};
    int ran = 0, failed = 0;
    for (int g = 0; g < 3; g++)
        for (const unit_test *t = groups[g]; t->name; t++) {
            if (list) {
                printf("%s\n", t->name);
                continue;
            }
            if (only && strcmp(only, t->name)) continue;
            int before = failures;
            log_clear();
            t->fn();
            ran++;
            if (failures != before) failed++;
            printf("%s %s\n", failures != before ? "FAIL" : "ok", t->name);
        }
    if (list) return 0;
    if (!ran) {
        fprintf(stderr, "no test named '%s'\n", only ? only : "");
        return 2;
    }
    return failed ? 1 : 0;
}
