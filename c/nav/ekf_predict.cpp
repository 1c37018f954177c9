#include "nav/ekf_predict.hpp"

#include <algorithm>
#include <cmath>

namespace nav {

namespace {

// Rates older than this are not used to turn the heading: the AHRS stopped.
constexpr double kGyroStaleS = 0.5;
// Heading random walk while the gyro is silent: an unknown turn rate of
// this order [rad/sqrt(s)], so the heading is not trusted for long.
constexpr double kHeadingWalkNoGyro = 0.3;

void predict_step(FilterState &s, double dt, bool gyro_fresh, const NavConfig &c)
{
    const Inputs &in = s.in;
    const double cphi = std::cos(in.roll_rad), sphi = std::sin(in.roll_rad);
    const double cth = std::max(std::cos(in.pitch_rad), 1e-3);
    // Euler kinematics: heading rate from the body rates
    const double psi_dot = gyro_fresh ? (in.q_radps * sphi + in.r_radps * cphi) / cth : 0.0;
    const double psi_mid = s.x(PSI) + 0.5 * psi_dot * dt;
    const Mat3 R = body_to_ned(in.roll_rad, in.pitch_rad, psi_mid);
    const Vec3 v = s.x.segment<3>(VU);

    Mat F = Mat::Identity();
    F.block<3, 3>(PN, VU) = R * dt;
    F.block<3, 1>(PN, PSI) = body_to_ned_dyaw(in.roll_rad, in.pitch_rad, psi_mid) * v * dt;

    s.x.segment<3>(PN) += R * v * dt;
    s.x(PSI) = wrap_2pi(s.x(PSI) + psi_dot * dt);

    s.P = F * s.P * F.transpose();
    const double hw = gyro_fresh ? c.heading_walk_rad_per_sqrt_s : kHeadingWalkNoGyro;
    const double gyro = c.gyro_noise_radps * dt;
    const double pw2 = c.position_walk_m_per_sqrt_s * c.position_walk_m_per_sqrt_s * dt;
    const bool in_waves = s.x(PD) < c.surface_zone_m;
    const double a = in_waves ? c.surface_accel_noise_mps2 : c.accel_noise_mps2;
    const double heave = in_waves ? c.surface_accel_noise_mps2 : c.heave_accel_noise_mps2;
    const double a2 = a * a * dt;
    const double cw2 = c.current_walk_mps_per_sqrt_s * c.current_walk_mps_per_sqrt_s * dt;
    s.P(PN, PN) += pw2;
    s.P(PE, PE) += pw2;
    s.P(PD, PD) += pw2;
    s.P(VU, VU) += a2;
    s.P(VV, VV) += a2;
    s.P(VW, VW) += heave * heave * dt;
    s.P(PSI, PSI) += hw * hw * dt + gyro * gyro;
    s.P(BIAS, BIAS) += c.compass_bias_walk_rad_per_sqrt_s * c.compass_bias_walk_rad_per_sqrt_s * dt;
    s.P(CN, CN) += cw2;
    s.P(CE, CE) += cw2;
}

}  // namespace

void init_state(FilterState &s, const NavConfig &c)
{
    s = FilterState();
    const double vv = c.initial_velocity_sigma_mps * c.initial_velocity_sigma_mps;
    const double cv = c.initial_current_sigma_mps * c.initial_current_sigma_mps;
    // Unknown until measured: large variances, replaced when each state is
    // first observed (reset_state).
    s.P.diagonal() << 1e6, 1e6, 1e4, vv, vv, vv, M_PI * M_PI,
        c.compass_bias_sigma_rad * c.compass_bias_sigma_rad, cv, cv;
}

void predict(FilterState &s, int64_t utime, const NavConfig &c)
{
    if (s.utime < 0) {
        s.utime = utime;
        return;
    }
    if (utime <= s.utime)
        return;
    // Before the heading is known, dead reckoning would integrate a
    // meaningless direction: time advances, the states wait.
    if (!s.heading_init) {
        s.utime = utime;
        return;
    }
    const double total = static_cast<double>(utime - s.utime) * 1e-6;
    // (capped: after a long silence, accuracy of the mean matters less than time)
    const int steps = std::min(1000, static_cast<int>(std::ceil(total / c.max_predict_step_s - 1e-9)));
    const double dt = total / (steps > 0 ? steps : 1);
    const bool gyro_fresh = s.in.gyro_utime >= 0 && static_cast<double>(s.utime - s.in.gyro_utime) * 1e-6 <= kGyroStaleS;
    for (int i = 0; i < steps; i++)
        predict_step(s, dt, gyro_fresh, c);
    s.utime = utime;
}

void reset_state(FilterState &s, int i, double value, double var)
{
    s.x(i) = value;
    s.P.row(i).setZero();
    s.P.col(i).setZero();
    s.P(i, i) = var;
}

}  // namespace nav
