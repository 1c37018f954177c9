/* The simulated vehicle's 6-DOF dynamics: the one copy of its equations.
 *
 *     M nu_dot + C_RB(nu) nu + [C_A(nu_r) nu_r + D(nu_r) nu_r] + g(eta) = tau
 *     eta_dot = J(eta) nu
 *
 * Fossen's form with Prestero's (2001) REMUS coefficients (docs/simulator.md,
 * "The model"). The simulator (python/sim/dynamics.py, class Dynamics) loads
 * build/lib/libauvdynamics.so with ctypes and calls auv_dyn_step() once per
 * physics step: the whole RK4 step is here, because in Python the right-hand
 * side's four calls per step were the simulator's hot path.
 *
 * Everything the equations read is one struct of doubles, auv_dyn_t, that
 * the caller allocates (auv_dyn_size() bytes) and fills. The caller finds each
 * field by name (auv_dyn_field()), so the layout is written down here only:
 * the binding holds no copy of it. Nothing here allocates, keeps state of its
 * own or fails: a step is a pure function of the struct.
 */
#ifndef AUV_DYNAMICS_H
#define AUV_DYNAMICS_H

#include <stddef.h>

/* The vehicle's constants, each named as sim.dynamics.Coefficients names it
 * (the binding copies that dataclass field by field, by these names). The
 * hydrodynamic ones are Prestero's coefficients (Xuu is X_u|u|, Yuudr is
 * Y_uu-delta-r); added_* are the added mass that a current's or the waves'
 * acceleration acts on (-Xud, -Yvd, -Zwd, -Mwd, -Nvd). */
#define AUV_DYN_CONSTANTS(X)                                                                             \
    X(mass_kg) X(xg) X(yg) X(zg) X(ixx) X(iyy) X(izz) X(weight_n) X(buoyancy_n) X(radius_m) X(g_mps2)    \
    X(Xuu) X(Xwq) X(Xqq) X(Xvr) X(Xrr)                                                                   \
    X(Yvv) X(Yrr) X(Yuv) X(Ywp) X(Yur) X(Ypq) X(Yuudr)                                                   \
    X(Zww) X(Zqq) X(Zuw) X(Zuq) X(Zvp) X(Zrp) X(Zuuds)                                                   \
    X(Kpp)                                                                                               \
    X(Mww) X(Mqq) X(Muw) X(Muq) X(Mvp) X(Mrp) X(Muuds)                                                   \
    X(Nvv) X(Nrr) X(Nuv) X(Nur) X(Nwp) X(Npq) X(Nuudr)                                                   \
    X(added_u) X(added_v) X(added_w) X(added_qw) X(added_rv)

typedef struct {
#define AUV_DYN_CONSTANT_FIELD(name) double name;
    AUV_DYN_CONSTANTS(AUV_DYN_CONSTANT_FIELD)
#undef AUV_DYN_CONSTANT_FIELD
    double minv[36]; /* M^-1, row by row: M = M_RB + M_A is constant, so the caller inverts it once */
    double dt;       /* the step [s] */
    /* The state: north, east, down [m], roll, pitch, yaw [rad] (ZYX Euler
     * angles: valid away from pitch = +-90 deg), then body velocities u, v, w
     * [m/s], p, q, r [rad/s]. A step keeps roll in (-pi, pi], yaw in [0, 2 pi). */
    double x[12];
    /* Inputs, held over a step (zero-order hold). */
    double rudder, stern;      /* fin angles in the coefficients' sign [rad] */
    double thrust, torque;     /* propeller [N], [N m] */
    double current_ned[3];     /* the water's velocity [m/s] */
    double water_accel_ned[3]; /* the water's acceleration [m/s^2] (waves) */
    double tau[6];             /* extra body forces [N] and moments [N m]; zeros: none */
    /* Out: the body acceleration at the start of the last step (RK4's first stage). */
    double nu_dot[6];
} auv_dyn_t;

/* sizeof(auv_dyn_t). */
size_t auv_dyn_size(void);
/* The byte offset of the field `name` (a constant, or minv, dt, x, rudder,
 * ..., nu_dot) and in *count its number of doubles; -1 for an unknown name. */
long auv_dyn_field(const char *name, size_t *count);
/* How many constants AUV_DYN_CONSTANTS lists (the binding checks it sets all). */
size_t auv_dyn_constant_count(void);

/* x_dot = f(x) with d's constants and inputs; x and xdot may not overlap. */
void auv_dyn_rhs(const auv_dyn_t *d, const double x[12], double xdot[12]);
/* One classic RK4 step of d->dt: updates d->x and d->nu_dot. */
void auv_dyn_step(auv_dyn_t *d);
/* The fraction of a horizontal cylinder's volume under water, its axis at
 * depth_m (positive down) and its radius radius_m. */
double auv_dyn_submerged_fraction(double depth_m, double radius_m);

#endif
