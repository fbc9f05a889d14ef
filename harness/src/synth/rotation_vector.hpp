// rotation_vector.hpp — rotations as rotation vectors (axis × angle, radians): the exponential and
// logarithm maps of SO(3), shared by the measured path's smoothing, the reference's turn and its fit.
#pragma once

#include <Eigen/Geometry>

namespace vobench::synth {

// The rotation by |w| about w / |w|; identity for (near) zero.
inline Eigen::Quaterniond exp_rotation(const Eigen::Vector3d& w) {
    const double angle = w.norm();
    if (angle < 1e-15) return Eigen::Quaterniond::Identity();
    return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

// The rotation vector of q (angle in [0, π]).
inline Eigen::Vector3d log_rotation(const Eigen::Quaterniond& q) {
    const Eigen::AngleAxisd aa(q.normalized());
    return aa.axis() * aa.angle();
}

}  // namespace vobench::synth
