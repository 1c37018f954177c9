/* chasm: check, draw and run mission plans offline.
 *
 *   chasm check [-P DIR] [-D name=value] PLAN...
 *   chasm dot   [-P DIR] [-D name=value] PLAN
 *   chasm outline PLAN
 *   chasm describe [-P DIR] PLUGIN...
 *   chasm run   [-P DIR] [-D name=value] PLAN --inputs FILE [--dt T] [--until T]
 *               [--watch VAR]... [--hotplug T:FILE]... [--expect PATH] [--trace]
 *
 * The plugin path is every -P/--plugin-path, then $CHASM_PLUGIN_PATH (":"-separated);
 * with neither, the plugins built beside this program (build/plugins). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chasm/chasm.h"
#include "chasm/chasm_structure.h"
#include "chasm_describe.h"
#include "chasm_findings.h"
#include "chasm_inputs.h"

#define MAXN 64

/* Every list on the command line holds MAXN; more is a usage error, never a
 * silent drop. */
static int too_many(const char *what)
{
    fprintf(stderr, "chasm: at most %d %s\n", MAXN, what);
    return -1;
}

/* A load error in an override (`<-D NAME>`) is a usage error: exit 2. */
static int override_error;

typedef struct {
    const char *dirs[MAXN];
    size_t n_dirs;
    const char *pn[MAXN], *pv[MAXN];
    size_t n_params;
    const char *plans[MAXN];
    size_t n_plans;
    const char *inputs, *expect;
    double dt_s, until_s;
    const char *watch[MAXN];
    size_t n_watch;
    double hp_t[MAXN];
    const char *hp_file[MAXN];
    size_t n_hp;
    int trace, verbose;
    char *env_copy;
    char self_plugins[4096];
} args_t;

static int usage_to(FILE *out, int rc)
{
    fputs("usage: chasm check [options] PLAN...\n"
          "       chasm dot [options] PLAN\n"
          "       chasm outline PLAN   (its states as parsed, even if it does not load: N PARENT FILE:LINE:COL PATH)\n"
          "       chasm describe [options] PLUGIN...   (behaviors and parameters of a plugin)\n"
          "       chasm run [options] PLAN --inputs FILE [--dt SECONDS] [--until SECONDS]\n"
          "                 [--watch VAR]... [--hotplug SECONDS:PLUGIN.so]... [--expect STATE/PATH] [--trace]\n"
          "options: -P, --plugin-path DIR   where plugins are found (also $CHASM_PLUGIN_PATH;\n"
          "                                 default: the build's plugins)\n"
          "         -D NAME=VALUE           override a plan parameter, e.g. -D depth='12 m'\n"
          "         -v, --verbose           print plugin and engine messages\n",
          out);
    return rc;
}

static int usage(void) { return usage_to(stderr, 2); }

static double seconds(const char *s)
{
    char *end;
    double v = strtod(s, &end);
    while (*end == ' ') end++;
    if (!strcmp(end, "ms")) v *= 1e-3;
    else if (!strcmp(end, "min")) v *= 60;
    else if (!strcmp(end, "h")) v *= 3600;
    else if (*end && strcmp(end, "s")) {
        fprintf(stderr, "chasm: '%s' is not a duration\n", s);
        exit(2);
    }
    if (end == s || !(v >= 0 && v <= 1e9)) { /* like durations in plans; no overflow in microseconds */
        fprintf(stderr, "chasm: '%s' is not a duration from 0 to 1e9 s\n", s);
        exit(2);
    }
    return v;
}

static int parse_args(int argc, char **argv, args_t *a)
{
    a->dt_s = 0.1;
    a->until_s = -1;
    for (int i = 2; i < argc; i++) {
        const char *s = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED() do { if (!val) { fprintf(stderr, "chasm: %s needs a value\n", s); return -1; } i++; } while (0)
        if (!strcmp(s, "-P") || !strcmp(s, "--plugin-path")) {
            NEED();
            if (a->n_dirs >= MAXN) return too_many("-P folders");
            a->dirs[a->n_dirs++] = val;
        } else if (!strcmp(s, "-D")) {
            NEED();
            const char *eq = strchr(val, '=');
            if (!eq) {
                fprintf(stderr, "chasm: -D wants NAME=VALUE, got '%s'\n", val);
                return -1;
            }
            if (a->n_params >= MAXN) return too_many("-D overrides");
            char *name = strndup(val, (size_t)(eq - val));
            a->pn[a->n_params] = name;
            a->pv[a->n_params++] = eq + 1;
        } else if (!strcmp(s, "--inputs")) {
            NEED();
            a->inputs = val;
        } else if (!strcmp(s, "--dt")) {
            NEED();
            a->dt_s = seconds(val);
        } else if (!strcmp(s, "--until")) {
            NEED();
            a->until_s = seconds(val);
        } else if (!strcmp(s, "--watch")) {
            NEED();
            if (a->n_watch >= MAXN) return too_many("--watch variables");
            a->watch[a->n_watch++] = val;
        } else if (!strcmp(s, "--expect")) {
            NEED();
            a->expect = val;
        } else if (!strcmp(s, "--hotplug")) {
            NEED();
            const char *colon = strchr(val, ':');
            if (a->n_hp >= MAXN) return too_many("--hotplug files");
            if (!colon) {
                fprintf(stderr, "chasm: --hotplug wants SECONDS:FILE, got '%s'\n", val);
                return -1;
            }
            char *t = strndup(val, (size_t)(colon - val));
            a->hp_t[a->n_hp] = seconds(t);
            free(t);
            a->hp_file[a->n_hp++] = colon + 1;
        } else if (!strcmp(s, "--trace")) a->trace = 1;
        else if (!strcmp(s, "-v") || !strcmp(s, "--verbose")) a->verbose = 1;
        else if (s[0] == '-' && s[1]) {
            fprintf(stderr, "chasm: unknown option '%s'\n", s);
            return -1;
        } else if (a->n_plans >= MAXN) return too_many("plans");
        else a->plans[a->n_plans++] = s;
    }
    const char *env = getenv("CHASM_PLUGIN_PATH");
    if (env && *env) {
        a->env_copy = strdup(env);
        for (char *save = NULL, *d = strtok_r(a->env_copy, ":", &save); d; d = strtok_r(NULL, ":", &save))
            if (a->n_dirs >= MAXN) return too_many("plugin folders (with $CHASM_PLUGIN_PATH)");
            else a->dirs[a->n_dirs++] = d;
    }
    /* Neither: the plugins built beside this program (build/bin/chasm ->
     * build/plugins), so `chasm check plan.chasm` works from a fresh build. */
    if (!a->n_dirs && chasm_default_plugin_dir(a->self_plugins, sizeof a->self_plugins))
        a->dirs[a->n_dirs++] = a->self_plugins;
    return 0;
}

static void on_log(void *user, int64_t now, const char *path, const char *msg)
{
    if (!*(int *)user) return;
    printf("%10.3f s  [%s] %s\n", (double)now * 1e-6, path && *path ? path : "chasm", msg);
}

static int verbose_flag;

static chasm_machine *load(const args_t *a, const char *plan)
{
    chasm_options o = {0};
    o.plugin_path = a->dirs;
    o.n_plugin_path = a->n_dirs;
    o.param_names = a->pn;
    o.param_values = a->pv;
    o.n_params = a->n_params;
    o.log = on_log;
    o.log_user = &verbose_flag;
    chasm_errors *e = NULL;
    chasm_machine *m = chasm_load_file(plan, &o, &e);
    for (size_t i = 0; i < chasm_errors_count(e); i++) {
        fprintf(stderr, "%s\n", chasm_errors_get(e, i));
        if (!strncmp(chasm_errors_get(e, i), "<-D ", 4)) override_error = 1;
    }
    if (e && chasm_errors_count(e) > 1) fprintf(stderr, "%s: %zu errors\n", plan, chasm_errors_count(e));
    chasm_errors_free(e);
    return m;
}

/* `chasm outline`: one line per parsed state, tab-separated, for views. */
static void print_outline(void *user, int index, int parent, const char *path, chasm_where w)
{
    (void)user;
    printf("%d\t%d\t%s:%d:%d\t%s\n", index, parent, w.file, w.line, w.col, path);
}

static void print_var(const chasm_machine *m, int id)
{
    switch (chasm_var_type(m, id)) {
    case CHASM_DOUBLE: printf(" %s=%g", chasm_var_name(m, id), chasm_var_get_double(m, id)); break;
    case CHASM_INT: printf(" %s=%lld", chasm_var_name(m, id), (long long)chasm_var_get_int(m, id)); break;
    case CHASM_BOOL: printf(" %s=%s", chasm_var_name(m, id), chasm_var_get_bool(m, id) ? "true" : "false"); break;
    case CHASM_STRING: printf(" %s=\"%s\"", chasm_var_name(m, id), chasm_var_get_string(m, id)); break;
    case CHASM_MESSAGES: {
        chasm_messages_info mi = {0};
        chasm_messages_stats(m, id, &mi);
        printf(" %s=<%llu messages>", chasm_var_name(m, id), (unsigned long long)mi.total);
        break;
    }
    }
}

static void print_line(const chasm_machine *m, int64_t now, const int *watch, size_t nw)
{
    chasm_status st;
    chasm_status_get(m, now, &st);
    if (st.run_state == CHASM_RUN_RUNNING || st.run_state == CHASM_RUN_PAUSED) printf("%10.3f s  %-32s", (double)now * 1e-6, st.leaf_path);
    else printf("%10.3f s  %-32s", (double)now * 1e-6, chasm_run_state_name(st.run_state));
    printf("  <- %s", st.last_condition);
    if (st.n_tests) {
        printf(" [");
        for (int i = 0; i < st.n_tests; i++) printf("%s%s=%s", i ? " " : "", st.test_name[i], st.test_value[i] ? "true" : "false");
        printf("]");
    }
    for (size_t i = 0; i < nw; i++) print_var(m, watch[i]);
    printf("\n");
}

static int cmd_run(const args_t *a)
{
    if (a->n_plans != 1 || !a->inputs) return usage();
    chasm_machine *m = load(a, a->plans[0]);
    if (!m) return 1;
    chasm_inputs in;
    if (chasm_inputs_read(a->inputs, m, &in)) {
        chasm_inputs_free(&in);
        chasm_free(m);
        return 1;
    }
    int watch[MAXN];
    for (size_t i = 0; i < a->n_watch; i++) {
        watch[i] = chasm_var_find(m, a->watch[i]);
        if (watch[i] < 0) {
            fprintf(stderr, "chasm: --watch: the plan has no variable '%s'\n", a->watch[i]);
            chasm_inputs_free(&in);
            chasm_free(m);
            return 1;
        }
    }
    int64_t dt = (int64_t)(a->dt_s * 1e6 + 0.5);
    if (dt <= 0) dt = 100000;
    int64_t last_in = in.n ? in.ev[in.n - 1].t_us : 0;
    int64_t until = a->until_s >= 0 ? (int64_t)(a->until_s * 1e6 + 0.5) : last_in + 60000000;
    size_t k = 0, h = 0;
    int64_t now = 0;
    int rc = 0;
    for (;; now += dt) {
        while (k < in.n && in.ev[k].t_us <= now) {
            const chasm_input_event *e = &in.ev[k++];
            switch (e->type) {
            case CHASM_DOUBLE: chasm_var_set_double(m, e->var, e->d, e->t_us); break;
            case CHASM_INT: chasm_var_set_int(m, e->var, (int64_t)e->d, e->t_us); break;
            case CHASM_BOOL: chasm_var_set_bool(m, e->var, e->b, e->t_us); break;
            case CHASM_STRING: chasm_var_set_string(m, e->var, e->s, e->t_us); break;
            case CHASM_MESSAGES: chasm_messages_append(m, e->var, e->s, e->s ? strlen(e->s) : 0, e->t_us); break;
            }
        }
        while (h < a->n_hp && (int64_t)(a->hp_t[h] * 1e6 + 0.5) <= now) {
            char err[2048];
            if (chasm_hotplug(m, a->hp_file[h], err, sizeof err))
                printf("%10.3f s  hot plug of '%s' failed: %s\n", (double)now * 1e-6, a->hp_file[h], err);
            else printf("%10.3f s  hot plug of '%s' done\n", (double)now * 1e-6, a->hp_file[h]);
            h++;
        }
        int64_t before = 0;
        chasm_status st;
        if (now == 0) {
            chasm_start(m, now);
            print_line(m, now, watch, a->n_watch);
        } else {
            chasm_status_get(m, now, &st);
            before = st.last_transition_us;
            int64_t cyc = st.cycle;
            (void)cyc;
            chasm_step(m, now);
            chasm_status_get(m, now, &st);
            if (st.last_transition_us != before || a->trace) print_line(m, now, watch, a->n_watch);
        }
        chasm_run_state r = chasm_run_state_of(m);
        if (r != CHASM_RUN_RUNNING || now >= until) break;
    }
    chasm_status st;
    chasm_status_get(m, now, &st);
    printf("%10.3f s  end: %s after %lld cycles, in %s\n", (double)now * 1e-6, chasm_run_state_name(st.run_state),
           (long long)st.cycle, st.run_state == CHASM_RUN_RUNNING ? st.leaf_path : st.last_from);
    if (st.run_state == CHASM_RUN_FAILED) rc = 3;
    if (a->expect) {
        const char *where = st.run_state == CHASM_RUN_RUNNING ? st.leaf_path : chasm_run_state_name(st.run_state);
        if (strcmp(where, a->expect)) {
            fprintf(stderr, "chasm: expected to end in '%s', ended in '%s'\n", a->expect, where);
            rc = 4;
        }
    }
    chasm_inputs_free(&in);
    chasm_free(m);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) return usage();
    /* `chasm --help` and `chasm CMD --help`: the usage on stdout, exit 0 */
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return usage_to(stdout, 0);
    args_t a = {0};
    if (parse_args(argc, argv, &a)) {
        for (size_t i = 0; i < a.n_params; i++) free((char *)a.pn[i]);
        free(a.env_copy);
        return 2;
    }
    verbose_flag = a.verbose;
    int rc = 0;
    if (!strcmp(argv[1], "check")) {
        if (!a.n_plans) rc = usage();
        for (size_t i = 0; i < a.n_plans; i++) {
            chasm_machine *m = load(&a, a.plans[i]);
            if (!m) {
                rc = 1;
                continue;
            }
            printf("%s: ok (%zu states, %zu tests, %zu variables", a.plans[i], chasm_state_count(m),
                   chasm_test_count(m), chasm_var_count(m));
            /* streams are named with their capacity: it is memory and the slow-reader margin */
            const char *sep = "; messages: ";
            for (size_t v = 0; v < chasm_var_count(m); v++) {
                chasm_messages_info mi;
                if (chasm_messages_stats(m, (int)v, &mi)) continue;
                printf("%s%s(%zu)", sep, chasm_var_name(m, (int)v), mi.capacity);
                sep = ", ";
            }
            printf(")\n");
            int found = chasm_check_deeper(m);
            if (found) printf("%s: %d finding%s\n", a.plans[i], found, found == 1 ? "" : "s");
            chasm_free(m);
        }
    } else if (!strcmp(argv[1], "dot")) {
        if (a.n_plans != 1) rc = usage();
        else {
            chasm_machine *m = load(&a, a.plans[0]);
            if (!m) rc = 1;
            else {
                chasm_write_dot(m, stdout);
                chasm_free(m);
            }
        }
    } else if (!strcmp(argv[1], "outline")) {
        if (a.n_plans != 1) rc = usage();
        else chasm_outline_file(a.plans[0], print_outline, NULL);
    } else if (!strcmp(argv[1], "describe")) {
        if (!a.n_plans) rc = usage();
        for (size_t i = 0; i < a.n_plans; i++) rc |= chasm_describe(a.dirs, a.n_dirs, a.plans[i]);
    } else if (!strcmp(argv[1], "run")) {
        rc = cmd_run(&a);
    } else rc = usage();
    for (size_t i = 0; i < a.n_params; i++) free((char *)a.pn[i]);
    free(a.env_copy);
    return rc == 1 && override_error ? 2 : rc;
}
