// alignment.hpp — aligning an estimated trajectory's positions to the ground truth before ATE.
//
//   se3     rotation + translation minimising Σ‖d_i − (R m_i + t)‖² in closed form (Horn 1987;
//           Umeyama 1991 eqs. 38–42 with c = 1) — what evaluate_ate.py does. The default.
//   sim3    the same with a scale c (Umeyama 1991 eq. 42), for monocular-style estimates.
//   posyaw  translation + rotation about the world z axis only (4 DoF), for data with known gravity.
//   none    identity: the estimate is compared in its own world frame.
// With first_n > 0 the transform is computed from the first n matched pairs only and applied to all.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <string>

namespace vobench::metrics {

enum class AlignmentMethod { Se3, Sim3, PosYaw, None };

AlignmentMethod parse_alignment(const std::string& name);  // throws std::invalid_argument
const char* alignment_name(AlignmentMethod method);

struct Alignment {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    double scale = 1.0;
    Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return scale * (R * p) + t; }
};

// `model` (estimate) and `data` (ground truth): matched positions, one per column.
// Throws std::invalid_argument when there are too few pairs for the method.
Alignment align(const Eigen::Matrix3Xd& model, const Eigen::Matrix3Xd& data, AlignmentMethod method, std::size_t first_n = 0);

}  // namespace vobench::metrics
