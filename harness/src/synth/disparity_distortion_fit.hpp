// disparity_distortion_fit.hpp — a Kinect v1's fixed disparity distortion, measured from a TUM-layout
// folder's depth images and its reference alone (issue #15; `vobench synth fit-distortion`; the numbers
// behind the `tum-fr1` camera's disparity_distortion_px, camera_catalog.cpp).
//
// Model (Herrera et al. 2012; Teichman et al. 2013): every measured disparity carries a fixed offset
// δ(x, y) = a·r² + b·x + c·y pixels (x, y pinhole-normalised pixel coordinates, r² = x² + y²), so a
// measured depth z_m was really z = f·b_IR / (f·b_IR / z_m − δ). The depth error grows as z²·δ / (f·b_IR)
// — harmless at 1 m, centimetres at 3–4 m — and stays with the camera, not the scene, so consecutive
// views of one surface disagree more the further the camera turned. The fit minimises that
// disagreement: frame i's corrected depth, moved by the reference's motion (poses at each depth image's
// tick on the stream's clock, camera_clock.hpp, less the stream's latency, stamp_latency.hpp) onto
// frame j's corrected depth
// (depth_pair_residuals, every 8th pixel), for pairs 4 and 16 frames apart starting at every second
// frame; Gauss–Newton on (a, b, c) from zero with a forward-difference Jacobian, robust by iterative
// reweighting (weights 1 / max(|r|, 0.5 %), residuals over 5 % dropped as occlusions). Optionally the
// latency and the turn of the frame the reference describes are fitted with the field (the joint fit).
#pragma once

#include "metrics/pose.hpp"
#include "synth/depth_geometry.hpp"
#include "synth/sensor_model.hpp"

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <vector>

namespace vobench::synth {

// A TUM-layout folder's depth stream in list order (consecutive frames) and its reference.
struct DepthSequence {
    std::vector<double> stamps;    // each image's tick on the clock fitted to the list's stamps (fit_camera_clock)
    std::vector<cv::Mat> depth_m;  // metres, CV_32FC1, 0 = missing, the camera's image size
    metrics::Trajectory reference;
};

// Reads depth.txt, every depth image it lists (or the first `max_frames`; 0: all; `depth_scale` units
// per metre) and groundtruth.txt. Throws std::runtime_error naming the file (and line) that is missing,
// malformed, not a 16-bit depth image or not the camera's size.
DepthSequence read_depth_sequence(const std::filesystem::path& folder, const PinholeCamera& camera, double depth_scale,
                                  std::size_t max_frames = 0);

using DisparityOffset = std::array<double, 3>;  // a, b, c in pixels

// The depth corrected for the offset: z = f·b / (f·b / z_m − δ(x, y)); 0 where z_m is 0 or the corrected
// disparity is not positive.
cv::Mat undo_disparity_offset(const cv::Mat& depth_m, const PinholeCamera& camera, const DisparityOffset& delta,
                              double focal_baseline_px_m);

struct DistortionFitOptions {
    double depth_latency_s = kinect1().depth_latency_s;  // the depth stream's latency (synth stats --camera measures it)
    // The frame the reference describes, in camera coordinates (a rotation vector, rad; reference_frame_error.hpp):
    // the camera's relative motion is X·(G_j⁻¹·G_i)·X⁻¹ for reference poses G and this turn X.
    Eigen::Vector3d reference_turn_rad = Eigen::Vector3d::Zero();
    double focal_baseline_px_m = 580 * 0.075;  // IR focal length × baseline (Khoshelham & Elberink 2012)
    int iterations = 14;
    // The joint fit: besides the field, the latency and/or the reference's turn are free (from the values
    // above). Why: a latency, a linear disparity field and a turn about the image's x axis all tilt the
    // residual the same way over a few frames, so fitting one with the others held can credit it with
    // theirs (docs/synthetic-sensors.md, "The reference's frame").
    bool fit_latency = false;
    bool fit_reference_turn = false;
};

struct DistortionFit {
    DisparityOffset delta{0, 0, 0};
    double depth_latency_s = 0;                                    // fitted, or the option's when held
    Eigen::Vector3d reference_turn_rad = Eigen::Vector3d::Zero();  // fitted, or the option's when held
    std::size_t pairs = 0;                                         // frame pairs the reference covers
    std::size_t residuals = 0;                                     // residuals in the last iteration's solve
};

// Throws std::runtime_error when no pair the reference covers overlaps, or the normal equations are
// singular (too few residuals to pin the free parameters down), or the options' latency or turn is
// not finite. A free latency stays within ±50 ms of
// its start (the pairs are those the reference covers over that whole range).
DistortionFit fit_disparity_distortion(const DepthSequence& sequence, const DepthRays& rays, const DistortionFitOptions& options);

// Median over pairs (k, k + gap), every k, of depth_pair_residual with the offset undone, in per cent
// of z (NaN: no pair), at the options' latency and reference turn; `pairs` gets how many counted.
double corrected_residual_pct(const DepthSequence& sequence, const DepthRays& rays, int gap, const DisparityOffset& delta,
                              const DistortionFitOptions& options, std::size_t& pairs);

// Writes a copy of the TUM-layout folder `in` into `out` with every depth image of depth.txt corrected for
// the offset (undo_disparity_offset, written back at `depth_scale` units per metre, 0 where missing); rgb.txt,
// depth.txt, groundtruth.txt and the colour images rgb.txt lists are copied unchanged. What it is for: how
// much of an algorithm's error on real frames the sensor's distortion causes (docs/synthetic-sensors.md).
// `out` must not exist or be empty, and every listed path must stay inside the folder (no absolute path,
// no `..`); both are checked before anything is written. Throws std::runtime_error naming the file (and
// the list entry) otherwise, or when an image cannot be read, is not a 16-bit depth image or not the
// camera's size. Returns the number of depth images written.
std::size_t write_corrected_folder(const std::filesystem::path& in, const std::filesystem::path& out, const PinholeCamera& camera,
                                   const DisparityOffset& delta, double focal_baseline_px_m, double depth_scale);

}  // namespace vobench::synth
