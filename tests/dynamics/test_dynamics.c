/* Unit tests of the vehicle's dynamics (c/dynamics/) on the shared harness:
 * properties the equations must have whatever the coefficients, so that the
 * sanitized build (ASan+UBSan) runs every path of the right-hand side and the
 * step. The figures of the REMUS 100 itself are held by the Python tests
 * (tests/sim/test_dynamics*.py, through the library sim.dynamics loads). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dynamics/auv_dynamics.h"
#include "../harness/unit.h"

/* A REMUS-like vehicle (the numbers only need to be plausible) with a
 * diagonal M^-1: CG under the CB, W = B. The caller frees it. */
static auv_dyn_t *vehicle(void)
{
    auv_dyn_t *d = calloc(1, auv_dyn_size()); /* exactly the size: ASan sees any overrun */
    d->mass_kg = 30.48;
    d->zg = 0.0196;
    d->ixx = 0.177;
    d->iyy = d->izz = 3.45;
    d->g_mps2 = 9.81;
    d->weight_n = d->buoyancy_n = d->mass_kg * d->g_mps2;
    d->radius_m = 0.0955;
    d->Xuu = -1.62, d->Xwq = -35.5, d->Xqq = -1.93, d->Xvr = 35.5, d->Xrr = -1.93;
    d->Yvv = -1310, d->Yrr = 0.632, d->Yuv = -28.6, d->Ywp = 35.5, d->Yur = 5.22, d->Ypq = 1.93, d->Yuudr = 9.64;
    d->Zww = -131, d->Zqq = -0.632, d->Zuw = -28.6, d->Zuq = -5.22, d->Zvp = -35.5, d->Zrp = 1.93, d->Zuuds = -9.64;
    d->Kpp = -0.130;
    d->Mww = 3.18, d->Mqq = -188, d->Muw = 24, d->Muq = -2, d->Mvp = -1.93, d->Mrp = 4.86, d->Muuds = -6.15;
    d->Nvv = -3.18, d->Nrr = -94, d->Nuv = -24, d->Nur = -2, d->Nwp = -1.93, d->Npq = -4.86, d->Nuudr = -6.15;
    d->added_u = 0.93, d->added_v = d->added_w = 35.5, d->added_qw = d->added_rv = 1.93;
    const double diag[6] = {d->mass_kg + 0.93, d->mass_kg + 35.5, d->mass_kg + 35.5, 0.177 + 0.0704, 3.45 + 4.88, 3.45 + 4.88};
    for (int i = 0; i < 6; i++)
        d->minv[7 * i] = 1.0 / diag[i];
    d->dt = 0.02;
    return d;
}

static void set_x(auv_dyn_t *d, const double x[12]) { memcpy(d->x, x, sizeof d->x); }

static void fields_name_every_member(void)
{
    size_t n = 0, covered = 0;
    const char *arrays[] = {"minv", "x", "current_ned", "water_accel_ned", "tau", "nu_dot"};
    const size_t lengths[] = {36, 12, 3, 3, 6, 6};
    for (int i = 0; i < 6; i++) {
        long off = auv_dyn_field(arrays[i], &n);
        CHECK(off >= 0 && n == lengths[i] && (size_t)off + n * sizeof(double) <= auv_dyn_size());
        covered += n;
    }
    const char *scalars[] = {"dt", "rudder", "stern", "thrust", "torque", "mass_kg", "Xuu", "added_rv"};
    for (int i = 0; i < 8; i++)
        CHECK(auv_dyn_field(scalars[i], &n) >= 0 && n == 1);
    CHECK_NEAR((double)auv_dyn_field("x", &n), (double)offsetof(auv_dyn_t, x), 0);
    CHECK(auv_dyn_field("no_such_field", &n) == -1);
    /* the arrays, 5 inputs and the constants fill the struct: none unnamed */
    covered += 5 + auv_dyn_constant_count();
    CHECK(covered * sizeof(double) == auv_dyn_size());
}

static void submerged_fraction_of_a_circle(void)
{
    const double r = 0.0955;
    CHECK(auv_dyn_submerged_fraction(r, r) == 1.0);
    CHECK(auv_dyn_submerged_fraction(-r, r) == 0.0);
    CHECK_NEAR(auv_dyn_submerged_fraction(0.0, r), 0.5, 1e-15);
    double last = 0.0;
    for (int i = 1; i < 50; i++) { /* inside: at the edges the segment's formula loses digits */
        const double z = r * (i / 25.0 - 1.0), f = auv_dyn_submerged_fraction(z, r);
        CHECK(f >= last && f <= 1.0);
        CHECK_NEAR(f + auv_dyn_submerged_fraction(-z, r), 1.0, 1e-12);
        last = f;
    }
}

static void neutral_hull_at_rest_stays(void)
{
    auv_dyn_t *d = vehicle();
    const double x0[12] = {1, 2, 20, 0, 0, 1.0, 0, 0, 0, 0, 0, 0};
    set_x(d, x0);
    for (int i = 0; i < 100; i++)
        auv_dyn_step(d);
    for (int i = 0; i < 12; i++)
        CHECK(d->x[i] == x0[i]);
    for (int i = 0; i < 6; i++)
        CHECK(d->nu_dot[i] == 0.0);
    free(d);
}

/* Every hydrodynamic term off and the CG at the CB: a tumbling free body
 * keeps its kinetic energy (RK4 at 50 Hz, 30 s). */
static void free_body_keeps_its_energy(void)
{
    auv_dyn_t *d = vehicle();
    auv_dyn_t k = *d;
    memset(d, 0, sizeof *d);
    d->mass_kg = k.mass_kg, d->ixx = k.ixx, d->iyy = k.iyy, d->izz = k.izz;
    d->weight_n = d->buoyancy_n = k.weight_n, d->g_mps2 = k.g_mps2, d->radius_m = k.radius_m, d->dt = 0.02;
    const double I[6] = {d->mass_kg, d->mass_kg, d->mass_kg, d->ixx, d->iyy, d->izz};
    for (int i = 0; i < 6; i++)
        d->minv[7 * i] = 1.0 / I[i];
    const double x0[12] = {0, 0, 50, 0.1, 0.2, 0.3, 1.0, 0.2, -0.1, 0.8, 0.05, 0.1};
    set_x(d, x0);
    double e0 = 0.0, e1 = 0.0;
    for (int i = 0; i < 6; i++)
        e0 += 0.5 * I[i] * d->x[6 + i] * d->x[6 + i];
    for (int i = 0; i < 1500; i++)
        auv_dyn_step(d);
    for (int i = 0; i < 6; i++)
        e1 += 0.5 * I[i] * d->x[6 + i] * d->x[6 + i];
    CHECK_NEAR(e1 / e0, 1.0, 1e-5);
    CHECK(d->x[3] > -M_PI && d->x[3] <= M_PI && d->x[5] >= 0.0 && d->x[5] < 2 * M_PI);
    free(d);
}

/* Moving with a uniform current, the hull sees no water flow: no force, so
 * (W = B, no rotation) no acceleration, whatever its heading and pitch. */
static void hull_moving_with_the_current_feels_nothing(void)
{
    auv_dyn_t *d = vehicle();
    d->zg = 0.0;
    const double cn = 0.3, ce = -0.2, psi = 1.0;
    d->current_ned[0] = cn, d->current_ned[1] = ce;
    const double x[12] = {0, 0, 20, 0, 0, psi, cos(psi) * cn + sin(psi) * ce, -sin(psi) * cn + cos(psi) * ce, 0, 0, 0, 0};
    double xdot[12];
    auv_dyn_rhs(d, x, xdot);
    for (int i = 6; i < 12; i++)
        CHECK_NEAR(xdot[i], 0.0, 1e-12);
    CHECK_NEAR(xdot[0], cn, 1e-12);
    CHECK_NEAR(xdot[1], ce, 1e-12);
    free(d);
}

/* Port and starboard are mirror images (y = 0 for the CG, no propeller
 * torque): mirroring the state, the rudder, the current and the waves
 * mirrors the derivative. Every term of the right-hand side takes part
 * (a current, waves, near the surface, extra forces). */
static void port_and_starboard_mirror(void)
{
    auv_dyn_t *d = vehicle();
    d->buoyancy_n = d->weight_n + 7.0;
    d->rudder = 0.2, d->stern = -0.1, d->thrust = 3.0;
    d->current_ned[0] = 0.2, d->current_ned[1] = 0.1, d->current_ned[2] = 0.02;
    d->water_accel_ned[0] = 0.1, d->water_accel_ned[1] = -0.3, d->water_accel_ned[2] = 0.2;
    d->tau[0] = 1.0, d->tau[2] = -2.0, d->tau[4] = 0.3;
    const double x[12] = {3, 4, 0.03, 0.2, -0.1, 0.7, 1.2, 0.1, -0.05, 0.3, 0.1, -0.2};
    /* which entries change sign in the mirror (y -> -y) */
    const double s[12] = {1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1};
    double xm[12], f[12], fm[12];
    for (int i = 0; i < 12; i++)
        xm[i] = s[i] * x[i];
    auv_dyn_rhs(d, x, f);
    d->rudder = -d->rudder, d->current_ned[1] = -d->current_ned[1], d->water_accel_ned[1] = -d->water_accel_ned[1];
    auv_dyn_rhs(d, xm, fm);
    for (int i = 0; i < 12; i++)
        CHECK_NEAR(fm[i], s[i] * f[i], 1e-12 * (1.0 + fabs(f[i])));
    free(d);
}

/* A step keeps roll in (-pi, pi] and yaw in [0, 2 pi), across either end. */
static void angles_wrap(void)
{
    auv_dyn_t *d = vehicle();
    const double cases[4][2] = {{M_PI - 1e-3, 2.0}, {-M_PI + 1e-3, -2.0}, {2 * M_PI - 1e-3, 0.5}, {1e-3, -0.5}};
    for (int c = 0; c < 4; c++) {
        double x[12] = {0, 0, 10, 0, 0, 1.0, 0, 0, 0, 0, 0, 0};
        if (c < 2)
            x[3] = cases[c][0], x[9] = cases[c][1];
        else
            x[5] = cases[c][0], x[11] = cases[c][1];
        set_x(d, x);
        auv_dyn_step(d);
        const double moved = c < 2 ? d->x[3] : d->x[5], before = cases[c][0];
        CHECK(d->x[3] > -M_PI && d->x[3] <= M_PI && d->x[5] >= 0.0 && d->x[5] < 2 * M_PI);
        CHECK(fabs(moved - before) > M_PI); /* it went across */
    }
    free(d);
}

static const unit_test tests[] = {
    {"fields_name_every_member", fields_name_every_member},
    {"submerged_fraction_of_a_circle", submerged_fraction_of_a_circle},
    {"neutral_hull_at_rest_stays", neutral_hull_at_rest_stays},
    {"free_body_keeps_its_energy", free_body_keeps_its_energy},
    {"hull_moving_with_the_current_feels_nothing", hull_moving_with_the_current_feels_nothing},
    {"port_and_starboard_mirror", port_and_starboard_mirror},
    {"angles_wrap", angles_wrap},
    {NULL, NULL},
};

int main(int argc, char **argv)
{
    unit_register_list(tests);
    return unit_main(argc, argv, NULL);
}
