#include "metrics/trajectory_stats.hpp"

#include "metrics/rpe.hpp"

#include <nlohmann/json.hpp>

namespace vobench::metrics {

TrajectoryStats compute_trajectory_stats(const Trajectory& trajectory, std::optional<double> rate_hz) {
    TrajectoryStats s;
    s.poses = trajectory.size();
    if (trajectory.empty()) return s;
    for (std::size_t k = 1; k < trajectory.size(); ++k) {
        s.length_m += (trajectory[k].p - trajectory[k - 1].p).norm();
        s.rotation_deg += rotation_angle(trajectory[k - 1].q.conjugate() * trajectory[k].q) * 180.0 / M_PI;
    }
    s.duration_s = rate_hz ? static_cast<double>(s.poses - 1) / *rate_hz : trajectory.back().t - trajectory.front().t;
    s.mean_velocity_mps = s.duration_s > 0 ? s.length_m / s.duration_s : 0.0;
    return s;
}

void to_json(nlohmann::json& j, const TrajectoryStats& s) {
    j = nlohmann::json{{"poses", s.poses},
                       {"duration_s", s.duration_s},
                       {"length_m", s.length_m},
                       {"mean_velocity_mps", s.mean_velocity_mps},
                       {"rotation_deg", s.rotation_deg}};
}

}  // namespace vobench::metrics
