// sequence_writer.hpp — `vobench synth`: renders a sequence and writes it in a data set layout.
//
// Layout `tum` (read by the tum reader): rgb/<t>.png, depth/<t>.png (16-bit, 5000 units per metre,
// registered to the colour image: Kinect v2 depth at 1920×1080), rgb.txt, depth.txt, groundtruth.txt
// (camera poses, TUM convention, full precision), camera.txt (colour intrinsics and distortion), plus
// marker_groundtruth.txt (PUTK² raw `id;rx;ry;rz;tx;ty;tz`) and camera_in_marker.txt (`x y z qw qx qy
// qz`) from which groundtruth.txt follows by eq. 10, and synth.json with every parameter used.
// Stamps are frame / 10 s (PUTK² records at 10 Hz), or with `stamps` those of a real TUM folder (colour and
// depth each at its own stamp); groundtruth.txt then holds the input trajectory's poses over the frames' span
// (±50 ms), as TUM's own files do.
//
// Layouts `putk2` (rgb_%05d.png, depth_%05d.png, matched.txt: `frame rgb depth`) and `putk2-tum`
// (rgb/, depth/, rgb.txt, depth.txt) hold the depth camera's own image in millimetres (Kinect v1:
// 320×240 registered; Kinect v2: 512×424 unregistered), groundtruth.txt with frame indices as stamps,
// PUTK²'s camData.txt, cameraZnacznik.txt and trajectory.txt, and for Kinect v2 depth_camera.txt.
// The putk2 reader reads both (datasets/README.md).
#pragma once

#include "metrics/pose.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace vobench::synth {

// Bumped whenever rendering changes what a seed produces: caches of older sequences are then stale.
// 3: rays traced in Embree packets, whose hit distances can differ from single rays' in the last
// float bit (measured: at most 0.1 % of a frame's pixels change, mostly by one grey level).
// 4: Kinect v1 loses returns in patches of its correlation window (SensorModel::dropout_window_px).
// 5: with --stamps, images exposed on the camera's regular clock, not at the jittering stamps
//    (effect stamp_jitter, camera_clock.hpp); built-in trajectories render as in 4.
// 6: desks are tops on legs; furniture other than desks and pillars against the walls, looked-at
//    desks only within 1.3 m, the nearest first; offices of at least 9 m for cameras that ask for
//    them (tum-fr1); Kinect v1's depth runs 6 px into the projector's shadow.
// 7: a trajectory file is rendered along its smoothed path, the file's poses kept as the reference
//    (effect measured_reference, measured_path.hpp); built-in trajectories render as in 6.
// 8: Kinect v1's auto-exposure follows the scene with τ 0.04 s instead of 0.3 s (measured on
//    fr1/rpy's brightness changes; SensorModel::exposure_time_constant_s).
// 9: Kinect v1's colour noise gains a smooth part (effect smooth_noise: 2.0 DN blurred to 1 px),
//    measured on fr1/rpy's flat-pixel noise; Kinect v2 renders as in 8.
// 10: tum-fr1: the reference written is turned by the camera's measured turn (effect
//    reference_frame_error, on by default; images unchanged), and the disparity field applied is
//    recalibrated so that renderings with that reference read back the real field. Other cameras as in 9.
// 11: Kinect v1's disparity error gains a smooth part, new each frame (effect correlated_depth_noise,
//    on by default, σ 0.06 px over 16 px), measured on fr1/rpy's one-frame depth residual by range.
//    Kinect v2 renders as in 10.
// 12: motion blur samples the exposure at the midpoints of its streak, each sample interpolated
//    between pixels: a streak under a pixel used to leave the image sharp (read at the nearest pixel),
//    so slow paths had no blur at all. Both sensors. Kinect v1's optics blur recalibrated with it
//    (σ 0.6 → 0.5 px, on the same edge-sharpness statistic).
// 13: Kinect v1's per-pixel disparity noise is averaged over a 7-px matching window (σ per pixel
//    kept), measured on the real fr1 frames' depth-noise correlation; its smooth part recalibrated with
//    it (σ 0.06 → 0.05 px); tum-fr1's reference turn (1.05 → 0.86°) and applied disparity field
//    recalibrated so that renderings read back the real ones again. Kinect v2 renders as in 12.
// 14: half the variance of Kinect v1's per-pixel disparity draw repeats at a pixel from frame to frame
//    while it sees about the same disparity (effect fixed_pattern_noise), measured on the real fr1
//    frames' depth-noise correlation with the same pixel in later frames. Kinect v2 renders as in 13.
// 15: every Kinect v1 unit's fixed disparity pattern beyond the low-order field (effect
//    disparity_pattern, a smooth field over ~100 px, drawn for each seed), measured on the real fr1/rpy
//    depth's fixed pattern (disparity_pattern.hpp). Kinect v2 renders as in 14.
constexpr int kGeneratorVersion = 15;

struct SynthOptions {
    std::string sensor = "kinect1";
    std::string trajectory = "explore1";          // a family name, or a file
    std::string trajectory_format = "putk2-raw";  // for a file: putk2-raw (marker) or tum (camera poses)
    std::string camera_in_marker;                 // putk2-raw file: override the sensor's camera-in-marker pose
    std::string camera;                           // colour camera: a name (camera_catalog.hpp) or file; empty: the sensor's
    std::filesystem::path stamps;                 // a TUM folder: render at its rgb.txt/depth.txt stamps (frame_plan.hpp)
    uint64_t frames = 0;                          // 0: the whole trajectory
    uint64_t seed = 1;
    std::string layout = "tum";
    bool blur = true;
    std::string effects;  // sensor_model.hpp parse_effects(): "" = the defaults
    std::filesystem::path out;
};

struct SynthReport {
    uint64_t frames = 0;
    uint64_t skipped_stamps = 0;  // --stamps pairs outside the trajectory's time span
    double seconds = 0;
    double fps() const { return seconds > 0 ? static_cast<double>(frames) / seconds : 0.0; }
};

// Throws std::invalid_argument / std::runtime_error with a message naming the option or file.
// `progress(done, total)` is called after each frame.
SynthReport synthesize(const SynthOptions& options, const std::function<void(uint64_t, uint64_t)>& progress = {});

}  // namespace vobench::synth
