#include "synth/reference_frame_error.hpp"

#include "synth/random_field.hpp"

#include <algorithm>
#include <cmath>

namespace vobench::synth {
namespace {
constexpr uint64_t kReferenceFrameSalt = 0x7265666672616d65ull;  // "refframe": apart from the renderer's streams
}

Eigen::Quaterniond reference_frame_error(uint64_t seed, double angle_rad) {
    if (angle_rad == 0) return Eigen::Quaterniond::Identity();
    // Uniform on the sphere: z uniform in [−1, 1], the azimuth uniform (Archimedes' hat-box theorem).
    const double z = 2.0 * uniform(hash(seed, kReferenceFrameSalt, 0)) - 1.0;
    const double azimuth = 2.0 * M_PI * uniform(hash(seed, kReferenceFrameSalt, 1));
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Eigen::Vector3d axis(r * std::cos(azimuth), r * std::sin(azimuth), z);
    return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, axis.normalized()));
}

void turn_reference_frame(metrics::Trajectory& poses, const Eigen::Quaterniond& turn) {
    for (auto& pose : poses) pose.q = (pose.q * turn).normalized();
}

}  // namespace vobench::synth
