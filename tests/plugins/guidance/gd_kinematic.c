#include <math.h>
#include <stdio.h>

#include "gd_tests.h"
#include "plugins/lib/pu_angle.h"

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

const char *plan_of(const char *text, int prelude)
{
    static char buf[16384];
    snprintf(buf, sizeof buf, "%s%s", prelude ? NAV_PRELUDE : "use guidance\n", text);
    return buf;
}

chasm_machine *gd_load(const char *text) { return pt_load(plan_of(text, 1)); }
const char *gd_errors(const char *text, int prelude) { return pt_errors(plan_of(text, prelude)); }

chasm_run_state fly(chasm_machine *m, kin_vehicle *v, double t, double dt)
{
    pt_set(m, "nav.north_m", v->n, t);
    pt_set(m, "nav.east_m", v->e, t);
    pt_set(m, "nav.depth_m", v->depth, t);
    pt_set(m, "nav.u_mps", v->u, t);
    chasm_run_state rs = chasm_step(m, (int64_t)llround(t * 1e6));
    double err = pu_wrap_pi(pt_get(m, "setpoint.heading_rad") - v->psi);
    double rate = fmax(-v->max_rate, fmin(v->max_rate, 0.8 * err));
    v->psi = pu_wrap_2pi(v->psi + rate * dt);
    v->n += (v->u * cos(v->psi) + v->cur_n) * dt;
    v->e += (v->u * sin(v->psi) + v->cur_e) * dt;
    return rs;
}
