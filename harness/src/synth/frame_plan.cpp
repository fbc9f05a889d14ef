#include "synth/frame_plan.hpp"

#include "metrics/association.hpp"
#include "synth/random_field.hpp"
#include "tum_lists.hpp"  // plugins/common
#include "util/files.hpp"

#include <algorithm>
#include <stdexcept>

namespace vobench::synth {
namespace {
constexpr uint64_t kStampOffsetSalt = 0x5d1f0ff5e7ull;
}  // namespace

std::vector<PlannedFrame> plan_every_pose(const metrics::Trajectory& camera) {
    std::vector<PlannedFrame> plan;
    plan.reserve(camera.size());
    for (std::size_t k = 0; k < camera.size(); ++k) {
        const auto& pose = camera[k];
        const auto& next = camera[std::min(k + 1, camera.size() - 1)];
        PlannedFrame f;
        f.color_stamp = f.depth_stamp = pose.t;
        f.color_pose = f.depth_pose = pose.isometry();
        f.next_pose = next.isometry();
        f.blur_interval_s = next.t - pose.t > 0 ? next.t - pose.t : 0.1;
        plan.push_back(f);
    }
    return plan;
}

void offset_depth_stamps(std::vector<PlannedFrame>& plan, const metrics::Trajectory& camera, uint64_t seed) {
    constexpr double kLargestOffset = 0.016;
    for (std::size_t k = 0; k < plan.size(); ++k) {
        const double offset = kLargestOffset * (2.0 * uniform(hash(seed, kStampOffsetSalt, k)) - 1.0);
        Eigen::Isometry3d pose;
        if (!interpolate_pose(camera, plan[k].color_stamp + offset, pose)) continue;  // at the ends: in sync
        plan[k].depth_stamp = plan[k].color_stamp + offset;
        plan[k].depth_pose = pose;
    }
}

bool interpolate_pose(const metrics::Trajectory& poses, double t, Eigen::Isometry3d& out) {
    if (poses.empty() || t < poses.front().t || t > poses.back().t) return false;
    const auto after = std::lower_bound(poses.begin(), poses.end(), t, [](const metrics::StampedPose& p, double s) { return p.t < s; });
    if (after->t == t || after == poses.begin()) {
        out = after->isometry();
        return true;
    }
    const auto& a = *(after - 1);
    const auto& b = *after;
    const double s = (t - a.t) / (b.t - a.t);
    out = Eigen::Isometry3d::Identity();
    out.linear() = a.q.slerp(s, b.q).normalized().toRotationMatrix();
    out.translation() = a.p + s * (b.p - a.p);
    return true;
}

std::vector<PlannedFrame> plan_from_tum_stamps(const metrics::Trajectory& camera, const std::filesystem::path& dir, std::size_t& skipped,
                                               const StampLatency& latency, bool on_camera_clock, StampClocks* clocks) {
    const auto rgb = tum::parse_list(read_file(dir / "rgb.txt"), (dir / "rgb.txt").string());
    const auto depth = tum::parse_list(read_file(dir / "depth.txt"), (dir / "depth.txt").string());
    std::vector<double> rgb_stamps, depth_stamps;
    for (const auto& e : rgb) rgb_stamps.push_back(e.stamp);
    for (const auto& e : depth) depth_stamps.push_back(e.stamp);
    metrics::AssociationOptions ao;  // TUM's associate.py default: 20 ms
    const auto pairs = metrics::associate(rgb_stamps, depth_stamps, ao);
    StampClocks fitted;
    if (on_camera_clock) fitted = {fit_camera_clock(rgb_stamps), fit_camera_clock(depth_stamps)};
    const std::vector<double>& rgb_ticks = on_camera_clock ? fitted.color.ticks : rgb_stamps;
    const std::vector<double>& depth_ticks = on_camera_clock ? fitted.depth.ticks : depth_stamps;
    constexpr double kBlurLookAhead = 0.01;  // seconds: the motion during the exposure, from the nearest poses
    std::vector<PlannedFrame> plan;
    skipped = 0;
    for (const auto& m : pairs.matches) {
        PlannedFrame f;
        f.color_stamp = rgb_stamps[m.first];
        f.depth_stamp = depth_stamps[m.second];
        const double color_exposed = rgb_ticks[m.first] - latency.color_s, depth_exposed = depth_ticks[m.second] - latency.depth_s;
        if (!interpolate_pose(camera, color_exposed, f.color_pose) || !interpolate_pose(camera, depth_exposed, f.depth_pose)) {
            ++skipped;
            continue;
        }
        f.blur_interval_s = kBlurLookAhead;
        if (!interpolate_pose(camera, color_exposed + kBlurLookAhead, f.next_pose)) {
            f.blur_interval_s = -kBlurLookAhead;  // at the end: look back, the caller's blur is symmetric
            if (!interpolate_pose(camera, color_exposed - kBlurLookAhead, f.next_pose)) f.next_pose = f.color_pose;
        }
        plan.push_back(f);
    }
    if (clocks) *clocks = std::move(fitted);
    if (plan.empty())
        throw std::runtime_error((dir / "rgb.txt").string() + ": no colour–depth pair lies inside the trajectory's time span (" +
                                 std::to_string(camera.empty() ? 0.0 : camera.front().t) + " to " +
                                 std::to_string(camera.empty() ? 0.0 : camera.back().t) + " s)");
    return plan;
}

Eigen::Isometry3d office_from_world(const std::vector<Eigen::Isometry3d>& poses, double floor_z) {
    double down_z = 0, lowest = 1e300;
    for (const auto& p : poses) {
        down_z += p.linear()(2, 1);  // world z of the camera's image-down axis
        lowest = std::min(lowest, p.translation().z());
    }
    if (poses.empty() || down_z >= 0) return Eigen::Isometry3d::Identity();  // z already points down
    const double world_floor = lowest < 0.3 ? lowest - 1.2 : 0.0;
    // (x, y, z) → (x, −y, floor_z − (z − world_floor)): a half turn about x, then the floors meet.
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
    T.translation() = Eigen::Vector3d(0, 0, floor_z + world_floor);
    return T;
}

}  // namespace vobench::synth
