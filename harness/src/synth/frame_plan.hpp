// frame_plan.hpp — where the cameras are when each image of a rendered sequence is taken.
//
// By default every pose of the trajectory is one frame, colour and depth taken at its stamp. With the
// stamps of a real TUM folder (`vobench synth --stamps DIR`), each associated colour–depth pair of
// DIR's rgb.txt and depth.txt is one frame: the colour image is rendered at the pose interpolated at
// its own stamp and the depth image at the pose at *its* stamp, so the real recording's
// unsynchronised streams (offsets of up to ~16 ms in fr1) and its dropped frames are reproduced. A
// recorded stamp is not the exposure, though: each image can be taken its stream's latency before its
// stamp (effect `stamp_latency`, measured with `vobench synth stats --camera`; stamp_latency.hpp), and
// on the camera's regular clock rather than at the jittering stamp (effect `stamp_jitter`;
// camera_clock.hpp).
#pragma once

#include "metrics/pose.hpp"
#include "synth/camera_clock.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace vobench::synth {

struct PlannedFrame {
    double color_stamp = 0, depth_stamp = 0;  // seconds
    Eigen::Isometry3d color_pose = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d depth_pose = Eigen::Isometry3d::Identity();  // of the colour camera at the depth stamp
    Eigen::Isometry3d next_pose = Eigen::Isometry3d::Identity();   // colour camera `blur_interval_s` later
    double blur_interval_s = 0.1;
    double exposure_reference = 0;  // linear mean luminance the auto-exposure is adapted to (0: this frame's)
};

// One frame per pose (colour and depth at the same stamp); the blur looks at the next pose.
std::vector<PlannedFrame> plan_every_pose(const metrics::Trajectory& camera);

// How long before its recorded stamp each stream's image is exposed (seconds; the middle row's time).
struct StampLatency {
    double color_s = 0;
    double depth_s = 0;
};

// One frame per colour–depth pair of `tum_folder` (TUM's association, pairs closer than 20 ms), poses
// interpolated in `camera` (position linearly, rotation by slerp) at each image's stamp — or, with
// `on_camera_clock`, its tick on the clock fitted to its stream's whole list (fit_camera_clock) —
// minus its stream's `latency`; the frame keeps the recorded stamps. Pairs outside the trajectory's
// time span are left out and counted in `skipped`. Throws std::runtime_error naming the file when the
// lists cannot be read or no pair lies inside the trajectory.
// The clocks fitted to a folder's two lists (with `on_camera_clock`; synth.json records them).
struct StampClocks {
    CameraClock color, depth;
};

std::vector<PlannedFrame> plan_from_tum_stamps(const metrics::Trajectory& camera, const std::filesystem::path& tum_folder,
                                               std::size_t& skipped, const StampLatency& latency = {}, bool on_camera_clock = false,
                                               StampClocks* clocks = nullptr);

// Effect `stamp_offsets` for built-in trajectories: each depth image is taken up to ±16 ms off its
// colour image (uniform, from the seed), as the unsynchronised Kinect v1 streams of TUM's fr1 show
// (`vobench synth stats`: mean 2.9 ms, largest 11–15 ms); the depth pose is interpolated at its stamp.
void offset_depth_stamps(std::vector<PlannedFrame>& plan, const metrics::Trajectory& camera, uint64_t seed);

// The pose at stamp t between the trajectory's neighbouring poses; false outside its span.
bool interpolate_pose(const metrics::Trajectory& poses, double t, Eigen::Isometry3d& out);

// The rigid motion from the trajectory's world frame to the office's (z down, floor at floor_z, as
// PUTK²'s): the identity for PUTK² paths; for a z-up world (TUM's motion capture), a half turn about
// x with the floor at z = 0 (or 1.2 m below the lowest pose when some pose is lower than 0.3 m). Which
// way is up is read off the cameras' image-down axes.
Eigen::Isometry3d office_from_world(const std::vector<Eigen::Isometry3d>& poses, double floor_z);

}  // namespace vobench::synth
