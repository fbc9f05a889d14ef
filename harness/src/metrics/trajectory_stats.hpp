// trajectory_stats.hpp — what Table 4 of Kraft et al. (2016) lists per sequence, and a little more.
#pragma once

#include "metrics/pose.hpp"

#include <nlohmann/json_fwd.hpp>

#include <optional>

namespace vobench::metrics {

struct TrajectoryStats {
    std::size_t poses = 0;
    double duration_s = 0;         // last − first stamp, or (poses − 1) / rate when a rate is given
    double length_m = 0;           // Σ ‖p_{k+1} − p_k‖
    double mean_velocity_mps = 0;  // length / duration
    double rotation_deg = 0;       // Σ angle(q_k⁻¹ q_{k+1})
};

// With `rate_hz`, duration counts frames at that rate, the way Table 4 does (frames = poses − 1).
TrajectoryStats compute_trajectory_stats(const Trajectory& trajectory, std::optional<double> rate_hz = {});

void to_json(nlohmann::json& j, const TrajectoryStats& s);

}  // namespace vobench::metrics
