// LBL two-way travel times. For each reply from transponder T at position
// x_T, pinged at t0 (the message time) and heard back after tau:
//   range z = (tau - turnaround) c / 2
//   h = (|x_T - p(t0)| + |x_T - p(t0 + tau)|) / 2,  p(t0 + tau) = p + R v tau
// so the vehicle's motion during the flight is in the model. The sound speed
// is the configured profile's mean along the path (c0 + g (d_vehicle +
// d_transponder) / 2) when the config gives one, else the message's. Each
// reply is a scalar update gated on its own, so one multipath outlier (always
// long) never takes the good replies of the same ping with it.
#include <cmath>

#include "nav/ekf_predict.hpp"
#include "nav/nav_updates.hpp"

namespace nav {

Outcome update_lbl(FilterState &s, const LblMeas &m, int64_t utime, const NavConfig &c)
{
    Outcome o;
    for (int i = 0; i < kMaxReplies; i++)
        o.reply_accepted[i] = -1;
    s.last_meas_utime[SENSOR_LBL] = utime;
    if (!s.aligned() || !s.depth_init)
        return o;               // ranges need a position to linearise about
    const double r = c.lbl_range_noise_m * c.lbl_range_noise_m;
    double worst_y2 = 0;
    for (int i = 0; i < m.n && i < kMaxReplies; i++) {
        const Transponder *t = c.transponder(m.id[i]);
        if (!t) {
            o.unknown++;
            continue;
        }
        const double cs = c.sound_speed_mps > 0
                              ? c.sound_speed_mps + c.sound_speed_gradient_per_m * 0.5 * (s.x(PD) + t->depth_m)
                              : m.sound_speed_mps;
        const double tau = m.two_way_travel_s[i];
        if (!(cs > 0) || !(tau > t->turnaround_s))
            continue;
        const double z = 0.5 * (tau - t->turnaround_s) * cs;
        const Mat3 R = body_to_ned(s.in.roll_rad, s.in.pitch_rad, s.x(PSI));
        const Vec3 v = s.x.segment<3>(VU);
        const Vec3 xt(t->north_m, t->east_m, t->depth_m);
        const Vec3 p0 = s.x.segment<3>(PN);
        const Vec3 p1 = p0 + R * v * tau;
        const Vec3 d0 = xt - p0, d1 = xt - p1;
        const double r0 = d0.norm(), r1 = d1.norm();
        if (r0 < 1e-3 || r1 < 1e-3)
            continue;
        const Vec3 u0 = d0 / r0, u1 = d1 / r1;
        Eigen::Matrix<double, 1, N> H = Eigen::Matrix<double, 1, N>::Zero();
        H.block<1, 3>(0, PN) = -0.5 * (u0 + u1).transpose();
        H.block<1, 3>(0, VU) = -0.5 * tau * u1.transpose() * R;
        H(PSI) = -0.5 * tau * u1.dot(body_to_ned_dyaw(s.in.roll_rad, s.in.pitch_rad, s.x(PSI)) * v);
        Eigen::Matrix<double, 1, 1> y, Rm;
        y(0) = z - 0.5 * (r0 + r1);
        Rm(0) = r;
        const Gated g = kalman_update<1>(s, y, H, Rm, c.gate_chi2[1]);
        s.last_nis[SENSOR_LBL] = o.nis = g.nis;
        o.reply_range_m[i] = z;
        o.reply_innovation_m[i] = y(0);
        o.reply_nis[i] = g.nis;
        o.reply_accepted[i] = g.accepted ? 1 : 0;
        if (g.accepted) {
            o.accepted++;
            s.last_accept_utime[SENSOR_LBL] = utime;
        } else {
            o.rejected++;
            worst_y2 = std::max(worst_y2, y(0) * y(0));
        }
    }
    // Consecutive pings with every reply rejected: the estimate, not three
    // transponders at once, is wrong. Widen the horizontal position by the
    // size of the misfit so the next ping can pull it back.
    if (o.accepted == 0 && o.rejected > 0) {
        if (++s.consecutive_rejects[SENSOR_LBL] >= c.reset_after[SENSOR_LBL]) {
            s.consecutive_rejects[SENSOR_LBL] = 0;
            s.P(PN, PN) += worst_y2;
            s.P(PE, PE) += worst_y2;
            o.reset = true;
        }
    } else if (o.accepted > 0) {
        s.consecutive_rejects[SENSOR_LBL] = 0;
    }
    return o;
}

}  // namespace nav
