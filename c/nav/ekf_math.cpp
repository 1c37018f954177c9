// Angles and rotations shared by the process and measurement models.
#include <cmath>

#include "nav/ekf_state.hpp"

namespace nav {

double wrap_2pi(double a)
{
    a = std::fmod(a, 2 * M_PI);
    if (a < 0)
        a += 2 * M_PI;
    return a >= 2 * M_PI ? 0.0 : a;     // -tiny + 2 pi rounds up to 2 pi
}

double wrap_pi(double a)
{
    a = wrap_2pi(a + M_PI) - M_PI;
    return a;
}

Mat3 body_to_ned(double roll, double pitch, double yaw)
{
    const double cf = std::cos(roll), sf = std::sin(roll), ct = std::cos(pitch), st = std::sin(pitch);
    const double cp = std::cos(yaw), sp = std::sin(yaw);
    Mat3 R;
    R << cp * ct, cp * st * sf - sp * cf, cp * st * cf + sp * sf,
         sp * ct, sp * st * sf + cp * cf, sp * st * cf - cp * sf,
         -st, ct * sf, ct * cf;
    return R;
}

Mat3 body_to_ned_dyaw(double roll, double pitch, double yaw)
{
    // d/dpsi Rz(psi) = Sz Rz(psi) with Sz the skew matrix of the z axis
    Mat3 R = body_to_ned(roll, pitch, yaw);
    Mat3 D = Mat3::Zero();
    D.row(0) = -R.row(1);
    D.row(1) = R.row(0);
    return D;
}

}  // namespace nav
