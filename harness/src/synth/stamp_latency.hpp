// stamp_latency.hpp — how long before its recorded stamp each stream's image was exposed, measured
// from a folder's images and its reference alone (issue #15; `vobench synth stats --camera`).
//
// A TUM list stamp is when the driver received the image, not when it was exposed. When the camera
// turns fast, an image taken 20 ms earlier than its stamp says is seen from a pose up to 2.5° away
// from the reference's pose at the stamp, and the error changes from frame to frame with the angular
// velocity — so no VO algorithm can beat it, and a rendering at the stamps is easier than the real
// recording. The latency L is the shift that makes consecutive images agree best with the reference
// when each is placed at the pose of (stamp − L):
//   depth: the median relative depth residual of frame i's depth moved onto frame j's
//     (depth_pair_residual, every 8th pixel);
//   colour: the median absolute grey-level difference between frame i (Gaussian-blurred, σ 1 px) at
//     its textured pixels (Sobel magnitude > 20) with valid registered depth and frame j at where
//     those points land (bilinear), i.e. photometric consistency.
// Each is summed over the gaps of 1, 2 and 4 frames (median over pairs per gap) and scanned over L in
// −10…40 ms in 2 ms steps; the estimate is the scan's minimum, refined between the steps by the vertex
// of the parabola through it and its neighbours. Checked on renderings with a known
// latency (tests/synth/stamp_latency_test.cpp) and measured on TUM fr1 (docs/synthetic-sensors.md).
#pragma once

#include "metrics/pose.hpp"
#include "synth/depth_geometry.hpp"

#include <opencv2/core.hpp>

#include <vector>

namespace vobench::synth {

// One stream's consecutive frames of a folder: the stamps, the grey images (colour; CV_8UC1) and the
// depth registered to them (metres, CV_32FC1, 0 = missing, the camera's image size).
struct LatencyFrames {
    std::vector<double> stamps;
    std::vector<cv::Mat> grey;     // empty for the depth stream
    std::vector<cv::Mat> depth_m;  // one per stamp
};

struct LatencyEstimate {
    double latency_ms = 0;    // the scan's minimum (NaN: no pair the reference covers)
    double cost_at_best = 0;  // the summed medians there (depth: % of z; colour: grey levels)
    double cost_at_zero = 0;  // ... and with the stamps taken as they are
    std::size_t pairs = 0;    // pairs with enough overlap at the best latency
};

// The depth stream's latency; `frames.depth_m` are the depth images at `frames.stamps`.
LatencyEstimate depth_latency(const LatencyFrames& frames, const metrics::Trajectory& reference, const DepthRays& rays);

// The colour stream's latency; `frames.grey` at `frames.stamps` with `frames.depth_m` registered to them
// (taken at their own, nearby stamps: the few pixels' motion between the two is smoothed by the blur).
LatencyEstimate color_latency(const LatencyFrames& frames, const metrics::Trajectory& reference, const DepthRays& rays);

struct ReadoutEstimate {
    double readout_ms = 0;    // the scan's minimum (NaN: no pair the reference covers)
    double cost_at_best = 0;  // the summed medians there (grey levels)
    double cost_at_zero = 0;  // ... and with every row exposed at once (a global shutter)
    std::size_t pairs = 0;
};

// The colour camera's rolling-shutter readout R: row v of an image exposed at (stamp − latency) +
// (v / rows − 1/2)·R, R scanned over 0…60 ms in 5-ms steps (refined as the latency is) with the colour
// cost above — each point carried into the world at its row's pose and into frame j at the pose of the
// row it lands on. `latency_ms` from color_latency.
ReadoutEstimate color_readout(const LatencyFrames& frames, const metrics::Trajectory& reference, const DepthRays& rays, double latency_ms);

// The depth (IR) camera's readout, the same way with the depth residual (depth_pair_residuals_rolling);
// `latency_ms` from depth_latency.
ReadoutEstimate depth_readout(const LatencyFrames& frames, const metrics::Trajectory& reference, const DepthRays& rays, double latency_ms);

}  // namespace vobench::synth
