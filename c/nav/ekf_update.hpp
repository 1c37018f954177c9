// The measurement update shared by every sensor: innovation gating on the
// normalised innovation squared (Mahalanobis distance), then a Joseph-form
// update (stays symmetric positive definite whatever the rounding).
#ifndef NAV_EKF_UPDATE_HPP
#define NAV_EKF_UPDATE_HPP

#include "nav/ekf_state.hpp"

namespace nav {

struct Gated {
    bool accepted = false;
    double nis = 0;             // y' S^-1 y
};

// y is the innovation z - h(x) (angles already wrapped), H its Jacobian, R the
// measurement covariance. The update is applied only if NIS <= gate.
//
// States in `consider` (a bit mask of StateIndex) are Schmidt "consider"
// states for this update: their estimate is not moved, but the covariance
// stays exact (the Joseph form holds for any gain). Used for the compass
// bias: only position fixes may move it (see nav_updates.hpp).
template <int M>
Gated kalman_update(FilterState &s, const Eigen::Matrix<double, M, 1> &y, const Eigen::Matrix<double, M, N> &H,
                    const Eigen::Matrix<double, M, M> &R, double gate, uint32_t consider = 0)
{
    using MatM = Eigen::Matrix<double, M, M>;
    const Eigen::Matrix<double, N, M> PHt = s.P * H.transpose();
    const MatM S = H * PHt + R;
    const Eigen::LLT<MatM> llt(S);
    Gated g;
    if (llt.info() != Eigen::Success)
        return g;               // S not positive definite: never trust such an update
    g.nis = y.dot(llt.solve(y));
    if (!(g.nis <= gate))
        return g;
    // K = P H' S^-1, computed as (S^-1 (P H')')' with the factorisation
    Eigen::Matrix<double, N, M> K = llt.solve(PHt.transpose()).transpose();
    for (int i = 0; i < N; i++)
        if (consider & (1u << i))
            K.row(i).setZero();
    s.x += K * y;
    const Mat IKH = Mat::Identity() - K * H;
    s.P = IKH * s.P * IKH.transpose() + K * R * K.transpose();
    s.P = 0.5 * (s.P + s.P.transpose()).eval();
    g.accepted = true;
    return g;
}

// The sizes the sensors use are compiled once, in ekf_update.cpp: each instance
// is a fully unrolled 10-state Joseph update, and compiling it in every sensor's
// file (with the sanitizers' checks on every element) was most of the build.
extern template Gated kalman_update<1>(FilterState &, const Eigen::Matrix<double, 1, 1> &,
                                       const Eigen::Matrix<double, 1, N> &, const Eigen::Matrix<double, 1, 1> &,
                                       double, uint32_t);
extern template Gated kalman_update<2>(FilterState &, const Eigen::Matrix<double, 2, 1> &,
                                       const Eigen::Matrix<double, 2, N> &, const Eigen::Matrix<double, 2, 2> &,
                                       double, uint32_t);
extern template Gated kalman_update<3>(FilterState &, const Eigen::Matrix<double, 3, 1> &,
                                       const Eigen::Matrix<double, 3, N> &, const Eigen::Matrix<double, 3, 3> &,
                                       double, uint32_t);

}  // namespace nav

#endif
