// The extended Kalman filter's state: ten states, fixed-size Eigen matrices,
// nothing allocated after construction.
//
//   x = [north, east, depth,            position in the world NED frame [m]
//        u, v, w,                       body velocity over ground [m/s]
//        psi,                           true heading [rad]
//        b,                             compass bias: compass = psi + b [rad]
//        current_n, current_e]          water current, NED [m/s] (seen by water track)
//
// Roll, pitch and the gyro rates are inputs taken from the AHRS (its roll and
// pitch are good to 0.1 deg, below what matters for navigation), not states.
#ifndef NAV_EKF_STATE_HPP
#define NAV_EKF_STATE_HPP

#include <cstdint>

#include <Eigen/Dense>

#include "nav/nav_meas.hpp"

namespace nav {

constexpr int N = 10;
enum StateIndex : int { PN = 0, PE, PD, VU, VV, VW, PSI, BIAS, CN, CE };

using Vec = Eigen::Matrix<double, N, 1>;
using Mat = Eigen::Matrix<double, N, N>;
using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

struct Inputs {
    double roll_rad = 0, pitch_rad = 0;
    double p_radps = 0, q_radps = 0, r_radps = 0;
    int64_t gyro_utime = -1;    // when the rates were measured; -1 never
};

// Everything a replay must restore to reprocess measurements exactly.
struct FilterState {
    int64_t utime = -1;         // time of validity of x and P; -1 before any measurement
    Vec x = Vec::Zero();
    Mat P = Mat::Zero();
    Inputs in;
    bool heading_init = false, position_init = false, velocity_init = false, depth_init = false;
    int consecutive_rejects[kSensors] = {0, 0, 0, 0, 0};
    int64_t last_accept_utime[kSensors] = {-1, -1, -1, -1, -1};
    int64_t last_meas_utime[kSensors] = {-1, -1, -1, -1, -1};
    double last_nis[kSensors] = {0, 0, 0, 0, 0};
    int64_t last_bottom_lock_utime = -1, last_water_track_utime = -1;

    bool aligned() const { return heading_init && position_init; }
};

// Body-to-NED rotation R = Rz(psi) Ry(theta) Rx(phi), and dR/dpsi.
Mat3 body_to_ned(double roll, double pitch, double yaw);
Mat3 body_to_ned_dyaw(double roll, double pitch, double yaw);
double wrap_pi(double a);
double wrap_2pi(double a);

}  // namespace nav

#endif
