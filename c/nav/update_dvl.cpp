// DVL velocity in body axes.
//   bottom lock: z = v (velocity over ground) + noise
//   water track: z = v - R(psi)' [current_n, current_e, 0] + noise
// Water track is velocity through the water, so it observes the body
// velocity only together with the current: the two current states carry it.
// Between position fixes the current is unobservable and its uncertainty
// grows the position's, as it should; a GPS or LBL fix makes it observable.
// Wave orbital motion and shear are not in the model: water track gets extra
// noise for them, largest near the surface (NavConfig).
#include <algorithm>
#include <cmath>

#include "nav/ekf_predict.hpp"
#include "nav/nav_updates.hpp"

namespace nav {

namespace {

// The body-frame velocity of the current in the state, and its Jacobians.
Vec3 current_body(const FilterState &s, Eigen::Matrix<double, 3, 2> *d_current, Vec3 *d_psi)
{
    const Mat3 R = body_to_ned(s.in.roll_rad, s.in.pitch_rad, s.x(PSI));
    const Vec3 c_ned(s.x(CN), s.x(CE), 0.0);
    if (d_current)
        *d_current = R.transpose().leftCols<2>();
    if (d_psi)
        *d_psi = body_to_ned_dyaw(s.in.roll_rad, s.in.pitch_rad, s.x(PSI)).transpose() * c_ned;
    return R.transpose() * c_ned;
}

void init_velocity(FilterState &s, const DvlMeas &m, double r)
{
    // velocity over ground = through the water + the current (estimate)
    const Vec3 vc = m.bottom_lock ? Vec3::Zero() : current_body(s, nullptr, nullptr);
    const double extra = m.bottom_lock ? 0.0 : s.P(CN, CN) + s.P(CE, CE);
    for (int i = 0; i < 3; i++)
        reset_state(s, VU + i, m.velocity_mps[i] + vc(i), r + extra);
    s.velocity_init = true;
}

}  // namespace

Outcome update_dvl(FilterState &s, const DvlMeas &m, int64_t utime, const NavConfig &c)
{
    Outcome o;
    double sigma = m.sigma_mps > 0 ? m.sigma_mps : c.dvl_noise_mps;
    double r = sigma * sigma;
    if (!m.bottom_lock) {
        // the water moves with the waves near the surface: little to learn there
        const double waves = c.dvl_water_track_surface_extra_mps * std::exp(-std::max(s.x(PD), 0.0) / c.wave_decay_depth_m);
        const double extra = c.dvl_water_track_extra_mps + waves;
        r += extra * extra;
    }
    s.last_meas_utime[SENSOR_DVL] = utime;
    // Water track needs the heading to put the current in body axes.
    if (!m.bottom_lock && !s.heading_init)
        return o;
    if (!s.velocity_init) {
        init_velocity(s, m, r);
        s.last_accept_utime[SENSOR_DVL] = utime;
        (m.bottom_lock ? s.last_bottom_lock_utime : s.last_water_track_utime) = utime;
        o.initialised = true;
        o.accepted = 1;
        return o;
    }
    const Vec3 z(m.velocity_mps[0], m.velocity_mps[1], m.velocity_mps[2]);
    Eigen::Matrix<double, 3, N> H = Eigen::Matrix<double, 3, N>::Zero();
    H.block<3, 3>(0, VU).setIdentity();
    Vec3 h = s.x.segment<3>(VU);
    if (!m.bottom_lock) {
        Eigen::Matrix<double, 3, 2> d_current;
        Vec3 d_psi;
        h -= current_body(s, &d_current, &d_psi);
        H.block<3, 2>(0, CN) = -d_current;
        // No heading column: the heading only rotates a current that is itself
        // barely known, and linearising about its estimate would invent heading
        // (and compass bias) information the data do not hold (the classic
        // EKF inconsistency of unobservable directions; seen here as a 0.3 deg
        // bias jump per update in the swell). Heading comes from the compass
        // and from position fixes.
        (void)d_psi;
    }
    const Vec3 y = z - h;
    const Mat3 R = Mat3::Identity() * r;
    const Gated g = kalman_update<3>(s, y, H, R, c.gate_chi2[3], kConsiderBias);
    if (g.accepted)
        (m.bottom_lock ? s.last_bottom_lock_utime : s.last_water_track_utime) = utime;
    if (record_gated(s, SENSOR_DVL, g, utime, c, o))
        init_velocity(s, m, r);
    return o;
}

}  // namespace nav
