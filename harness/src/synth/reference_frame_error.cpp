#include "synth/reference_frame_error.hpp"

#include "synth/rotation_vector.hpp"

#include <cmath>

namespace vobench::synth {

Eigen::Quaterniond reference_turn(const std::array<double, 3>& rotation_vector_deg) {
    return exp_rotation(Eigen::Vector3d(rotation_vector_deg[0], rotation_vector_deg[1], rotation_vector_deg[2]) * (M_PI / 180.0));
}

void turn_reference_frame(metrics::Trajectory& poses, const Eigen::Quaterniond& turn) {
    for (auto& pose : poses) pose.q = (pose.q * turn).normalized();
}

}  // namespace vobench::synth
