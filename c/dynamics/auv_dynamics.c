/* The vehicle's 6-DOF dynamics (auv_dynamics.h): right-hand side and RK4.
 *
 * Written to compute what the Python implementation it replaced computed, to
 * the last bit where the C library's sin/cos/acos/sqrt are the ones Python
 * called: every sum and product is in the same order (C and Python both
 * evaluate a + b + c as (a + b) + c), angles wrap as Python's % does, and
 * -std=c11 keeps GCC from fusing a * b + c into one rounding (FMA).
 * tests/sim/test_dynamics_reference.py holds it to that implementation's
 * figures.
 */
#include "dynamics/auv_dynamics.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846 /* rounds to Python's math.pi */
#define TWO_PI (2.0 * PI)

#define COUNT_OF(member) (sizeof(((auv_dyn_t *)0)->member) / sizeof(double))
#define FIELD(member) {#member, offsetof(auv_dyn_t, member), COUNT_OF(member)},

static const struct {
    const char *name;
    size_t offset, count;
} fields[] = {
    AUV_DYN_CONSTANTS(FIELD) FIELD(minv) FIELD(dt) FIELD(x) FIELD(rudder) FIELD(stern) FIELD(thrust)
        FIELD(torque) FIELD(current_ned) FIELD(water_accel_ned) FIELD(tau) FIELD(nu_dot)};

#define ONE(name) +1
static const size_t constant_count = 0 AUV_DYN_CONSTANTS(ONE);
#undef ONE

size_t auv_dyn_size(void) { return sizeof(auv_dyn_t); }

size_t auv_dyn_constant_count(void) { return constant_count; }

long auv_dyn_field(const char *name, size_t *count)
{
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++)
        if (strcmp(fields[i].name, name) == 0) {
            *count = fields[i].count;
            return (long)fields[i].offset;
        }
    return -1;
}

double auv_dyn_submerged_fraction(double depth_m, double radius_m)
{
    /* Why: with a positively buoyant hull the buoyancy must fall as the hull
     * breaks the surface, or the vehicle would fly out of the water. The
     * section is a circle: the area of the segment below the surface. */
    if (depth_m >= radius_m)
        return 1.0;
    if (depth_m <= -radius_m)
        return 0.0;
    const double h = depth_m + radius_m; /* submerged height of the section */
    const double rr = radius_m;
    const double chord2 = 2.0 * rr * h - h * h; /* can round below 0 */
    const double seg = rr * rr * acos((rr - h) / rr) - (rr - h) * sqrt(0.0 > chord2 ? 0.0 : chord2);
    return seg / (PI * rr * rr);
}

void auv_dyn_rhs(const auv_dyn_t *d, const double x[12], double xdot[12])
{
    const double z = x[2], phi = x[3], theta = x[4], psi = x[5];
    const double u = x[6], v = x[7], w = x[8], p = x[9], q = x[10], r = x[11];
    const double m = d->mass_kg, xg = d->xg, yg = d->yg, zg = d->zg;
    const double W = d->weight_n, B = d->buoyancy_n, rad = d->radius_m;
    const double dr = d->rudder, ds = d->stern;
    const double cphi = cos(phi), sphi = sin(phi);
    const double cth = cos(theta), sth = sin(theta);
    const double cpsi = cos(psi), spsi = sin(psi);
    /* rotation body -> NED */
    const double r00 = cpsi * cth;
    const double r01 = cpsi * sth * sphi - spsi * cphi;
    const double r02 = spsi * sphi + cpsi * cphi * sth;
    const double r10 = spsi * cth;
    const double r11 = cpsi * cphi + sphi * sth * spsi;
    const double r12 = sth * spsi * cphi - cpsi * sphi;
    const double r20 = -sth;
    const double r21 = cth * sphi;
    const double r22 = cth * cphi;

    /* Hydrodynamic terms see the velocity relative to the water, nu_r = nu -
     * nu_c (the current in body axes); rigid-body terms the velocity over ground. */
    const double cn = d->current_ned[0], ce = d->current_ned[1], cd = d->current_ned[2];
    double uc = 0.0, vc = 0.0, wc = 0.0, ur = u, vr = v, wr = w;
    if (cn != 0.0 || ce != 0.0 || cd != 0.0) {
        uc = r00 * cn + r10 * ce + r20 * cd;
        vc = r01 * cn + r11 * ce + r21 * cd;
        wc = r02 * cn + r12 * ce + r22 * cd;
        ur = u - uc;
        vr = v - vc;
        wr = w - wc;
    }
    const double uau = ur * fabs(ur), vav = vr * fabs(vr), waw = wr * fabs(wr);

    /* hydrostatics: buoyancy falls as the hull breaks the surface */
    const double fw = W - (z >= rad ? B : B * auv_dyn_submerged_fraction(z, rad));
    const double ex = -sth, ey = r21, ez = r22; /* gravity's direction, body frame */
    const double pp = p * p, qq = q * q, rr = r * r;
    const double ap = fabs(p), aq = fabs(q), ar = fabs(r);

    /* The bracket term by term in Prestero's coefficient form: his combined
     * coefficients (Yur, Muw, ...) already hold the C_A entries linear in u,
     * so C_A is not built from M_A as well (that would count the Munk moment
     * twice). Then C_RB(nu) nu and g(eta): weight at the CG, buoyancy at the
     * CB (the body origin), so only the weight has a moment, W (r_g x e). */
    double X = d->Xuu * uau + d->Xwq * wr * q + d->Xqq * qq + d->Xvr * vr * r + d->Xrr * rr +
               m * (v * r - w * q + xg * (qq + rr) - yg * p * q - zg * p * r) + fw * ex + d->thrust;
    double Y = d->Yvv * vav + d->Yrr * r * ar + d->Yuv * ur * vr + d->Ywp * wr * p + d->Yur * ur * r +
               d->Ypq * p * q + d->Yuudr * uau * dr + m * (w * p - u * r + yg * (rr + pp) - zg * q * r - xg * q * p) +
               fw * ey;
    double Z = d->Zww * waw + d->Zqq * q * aq + d->Zuw * ur * wr + d->Zuq * ur * q + d->Zvp * vr * p +
               d->Zrp * r * p + d->Zuuds * uau * ds + m * (u * q - v * p + zg * (pp + qq) - xg * r * p - yg * r * q) +
               fw * ez;
    double K = d->Kpp * p * ap - (d->izz - d->iyy) * q * r - m * (yg * (v * p - u * q) - zg * (u * r - w * p)) +
               W * (yg * ez - zg * ey) + d->torque;
    double Mm = d->Mww * waw + d->Mqq * q * aq + d->Muw * ur * wr + d->Muq * ur * q + d->Mvp * vr * p +
               d->Mrp * r * p + d->Muuds * uau * ds - (d->ixx - d->izz) * r * p -
               m * (zg * (w * q - v * r) - xg * (v * p - u * q)) + W * (zg * ex - xg * ez);
    double N = d->Nvv * vav + d->Nrr * r * ar + d->Nuv * ur * vr + d->Nur * ur * r + d->Nwp * wr * p +
               d->Npq * p * q + d->Nuudr * uau * dr - (d->iyy - d->ixx) * p * q -
               m * (xg * (u * r - w * p) - yg * (w * q - v * r)) + W * (xg * ey - yg * ex);

    /* Added mass acts on the relative acceleration: + M_A nu_c_dot with
     * nu_c_dot = v_c^b x omega for a current fixed in NED, or a hull moving
     * with the water would feel a force while it turns. */
    if (uc != 0.0 || vc != 0.0 || wc != 0.0) {
        const double acv = wc * p - uc * r;
        const double acw = uc * q - vc * p;
        X += d->added_u * (vc * r - wc * q);
        Y += d->added_v * acv;
        Z += d->added_w * acw;
        Mm += d->added_qw * acw;
        N += d->added_rv * acv;
    }
    /* The water accelerates (waves): the pressure gradient that drives it
     * pushes on the displaced volume (Froude-Krylov, rho V a, at the CB, so
     * no moment) and the added mass follows the water, + M_A R^T a (its w and
     * v columns couple into pitch and yaw). */
    const double an = d->water_accel_ned[0], ae = d->water_accel_ned[1], ad = d->water_accel_ned[2];
    if (an != 0.0 || ae != 0.0 || ad != 0.0) {
        const double rho_v = (W - fw) / d->g_mps2; /* displaced mass, less when surfacing */
        const double abx = r00 * an + r10 * ae + r20 * ad;
        const double aby = r01 * an + r11 * ae + r21 * ad;
        const double abz = r02 * an + r12 * ae + r22 * ad;
        X += (rho_v + d->added_u) * abx;
        Y += (rho_v + d->added_v) * aby;
        Z += (rho_v + d->added_w) * abz;
        Mm += d->added_qw * abz;
        N += d->added_rv * aby;
    }
    X += d->tau[0];
    Y += d->tau[1];
    Z += d->tau[2];
    K += d->tau[3];
    Mm += d->tau[4];
    N += d->tau[5];

    /* eta_dot = J(eta) nu; nu_dot = M^-1 (the sum of the forces) */
    const double tth = sth / cth;
    xdot[0] = r00 * u + r01 * v + r02 * w;
    xdot[1] = r10 * u + r11 * v + r12 * w;
    xdot[2] = r20 * u + r21 * v + r22 * w;
    xdot[3] = p + sphi * tth * q + cphi * tth * r;
    xdot[4] = cphi * q - sphi * r;
    xdot[5] = (sphi * q + cphi * r) / cth;
    for (int i = 0; i < 6; i++) {
        const double *mi = d->minv + 6 * i;
        xdot[6 + i] = mi[0] * X + mi[1] * Y + mi[2] * Z + mi[3] * K + mi[4] * Mm + mi[5] * N;
    }
}

/* a % b as Python computes it for floats: the sign of b (fmod gives a's). */
static double py_mod(double a, double b)
{
    double mod = fmod(a, b);
    if (mod != 0.0) {
        if ((b < 0.0) != (mod < 0.0))
            mod += b;
    } else {
        mod = copysign(0.0, b);
    }
    return mod;
}

void auv_dyn_step(auv_dyn_t *d)
{
    /* Classic RK4, inputs held: each stage's state is x + h k with h = dt/2,
     * dt/2, dt, and x_next = x + dt/6 (k1 + 2 (k2 + k3) + k4). */
    const double dt = d->dt, h = 0.5 * dt, wt = dt / 6.0;
    double *x = d->x;
    double k1[12], k2[12], k3[12], k4[12], s[12];
    auv_dyn_rhs(d, x, k1);
    for (int i = 0; i < 12; i++)
        s[i] = x[i] + h * k1[i];
    auv_dyn_rhs(d, s, k2);
    for (int i = 0; i < 12; i++)
        s[i] = x[i] + h * k2[i];
    auv_dyn_rhs(d, s, k3);
    for (int i = 0; i < 12; i++)
        s[i] = x[i] + dt * k3[i];
    auv_dyn_rhs(d, s, k4);
    for (int i = 0; i < 12; i++)
        x[i] = x[i] + wt * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
    /* keep roll in (-pi, pi] and yaw in [0, 2 pi) */
    if (x[3] > PI || x[3] <= -PI)
        x[3] = py_mod(x[3] + PI, TWO_PI) - PI;
    x[5] = py_mod(x[5], TWO_PI);
    memcpy(d->nu_dot, k1 + 6, sizeof d->nu_dot);
}
