#include <math.h>
#include <stdlib.h>

#include "gd_test.h"
#include "plugins/guidance/gd_geometry.h"
#include "plugins/lib/pu_angle.h"

int failures;
char logbuf[8192];
static const char *plugin_dir = ".";

const char *const NAV_PRELUDE =
    "use guidance\n"
    "input  nav.north_m : double m\n"
    "input  nav.east_m : double m\n"
    "input  nav.depth_m : double m\n"
    "input  nav.altitude_m : double m\n"
    "input  nav.u_mps : double m/s\n"
    "input  gps.fix_type : int\n"
    "output setpoint.heading_rad : double rad\n"
    "output setpoint.vertical_mode : int\n"
    "output setpoint.depth_m : double m\n"
    "output setpoint.altitude_m : double m\n"
    "output setpoint.pitch_rad : double rad\n"
    "output setpoint.speed_mode : int\n"
    "output setpoint.speed_mps : double m/s\n"
    "output setpoint.prop_rpm : double\n";

int first_line(void)
{
    int n = 1;
    for (const char *p = NAV_PRELUDE; *p; p++)
        n += *p == '\n';
    return n;
}

static void on_log(void *user, int64_t now, const char *path, const char *msg)
{
    (void)user;
    (void)now;
    (void)path;
    size_t L = strlen(logbuf);
    snprintf(logbuf + L, sizeof logbuf - L, "%s;", msg);
}

static chasm_machine *load_with(const char *text, chasm_errors **e, int prelude)
{
    static char buf[16384];
    snprintf(buf, sizeof buf, "%s%s", prelude ? NAV_PRELUDE : "use guidance\n", text);
    const char *dirs[] = {plugin_dir};
    chasm_options o = {0};
    o.plugin_path = dirs;
    o.n_plugin_path = 1;
    o.log = on_log;
    return chasm_load_string("t.chasm", buf, strlen(buf), &o, e);
}

chasm_machine *load(const char *text)
{
    chasm_errors *e = NULL;
    chasm_machine *m = load_with(text, &e, 1);
    for (size_t i = 0; i < chasm_errors_count(e); i++)
        fprintf(stderr, "%s\n", chasm_errors_get(e, i));
    chasm_errors_free(e);
    if (!m) {
        failures++;
        fprintf(stderr, "plan did not load\n");
    }
    return m;
}

const char *load_errors(const char *text, int prelude)
{
    static char buf[4096];
    chasm_errors *e = NULL;
    chasm_machine *m = load_with(text, &e, prelude);
    buf[0] = 0;
    for (size_t i = 0; i < chasm_errors_count(e); i++)
        snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%s\n", chasm_errors_get(e, i));
    chasm_errors_free(e);
    chasm_free(m);
    return buf;
}

static int var(chasm_machine *m, const char *name)
{
    int id = chasm_var_find(m, name);
    if (id < 0) {
        fprintf(stderr, "no variable %s\n", name);
        failures++;
    }
    return id;
}

double var_d(chasm_machine *m, const char *name) { return chasm_var_get_double(m, var(m, name)); }
void set_var_d(chasm_machine *m, const char *name, double v, double t)
{
    chasm_var_set_double(m, var(m, name), v, (int64_t)llround(t * 1e6));
}
void set_var_i(chasm_machine *m, const char *name, long v, double t)
{
    chasm_var_set_int(m, var(m, name), v, (int64_t)llround(t * 1e6));
}

const char *leaf(chasm_machine *m)
{
    static chasm_status st;
    chasm_status_get(m, 0, &st);
    return st.leaf_path;
}

chasm_run_state fly(chasm_machine *m, kin_vehicle *v, double t, double dt)
{
    set_var_d(m, "nav.north_m", v->n, t);
    set_var_d(m, "nav.east_m", v->e, t);
    set_var_d(m, "nav.depth_m", v->depth, t);
    set_var_d(m, "nav.u_mps", v->u, t);
    chasm_run_state rs = chasm_step(m, (int64_t)llround(t * 1e6));
    double err = pu_wrap_pi(var_d(m, "setpoint.heading_rad") - v->psi);
    double rate = fmax(-v->max_rate, fmin(v->max_rate, 0.8 * err));
    v->psi = pu_wrap_2pi(v->psi + rate * dt);
    v->n += (v->u * cos(v->psi) + v->cur_n) * dt;
    v->e += (v->u * sin(v->psi) + v->cur_e) * dt;
    return rs;
}

static int run_list(const unit_test *list, const char *only, int *ran)
{
    for (const unit_test *t = list; t->name; t++) {
        if (only && strcmp(only, t->name))
            continue;
        int before = failures;
        logbuf[0] = 0;
        t->fn();
        printf("%s %s\n", failures == before ? "ok" : "FAIL", t->name);
        (*ran)++;
    }
    return 0;
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
    int ran = 0;
    run_list(geometry_tests, only, &ran);
    run_list(behavior_tests, only, &ran);
    if (!ran) {
        fprintf(stderr, "no test named %s\n", only ? only : "(any)");
        return 2;
    }
    return failures ? 1 : 0;
}
