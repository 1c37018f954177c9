// The measurement updates of the sizes the sensors use, instantiated once
// (declared extern in ekf_update.hpp).
#include "nav/ekf_update.hpp"

namespace nav {

template Gated kalman_update<1>(FilterState &, const Eigen::Matrix<double, 1, 1> &, const Eigen::Matrix<double, 1, N> &,
                                const Eigen::Matrix<double, 1, 1> &, double, uint32_t);
template Gated kalman_update<2>(FilterState &, const Eigen::Matrix<double, 2, 1> &, const Eigen::Matrix<double, 2, N> &,
                                const Eigen::Matrix<double, 2, 2> &, double, uint32_t);
template Gated kalman_update<3>(FilterState &, const Eigen::Matrix<double, 3, 1> &, const Eigen::Matrix<double, 3, N> &,
                                const Eigen::Matrix<double, 3, 3> &, double, uint32_t);

}  // namespace nav
