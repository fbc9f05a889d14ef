// depth_noise_persistence.hpp — how much of a depth camera's noise comes back in the next frames at the
// same pixel (issue #15; `vobench synth stats`). A structured-light camera's disparity error at a pixel
// depends on the projector's speckle its matching window sees there, which the rigid projector and
// camera show again whenever the pixel sees about the same disparity: on TUM's fr1 frames the
// residuals of planar patches correlate from one frame to the next at the same pixel, and less at a
// few pixels' offset — the camera's own pattern, not the scene's, which moves across the image.
// Noise drawn anew every frame reads about 0.
//
// Measured on pairs (k, k + gap) of the folder's depth images (consecutive in depth.txt): in every
// 32×32 patch that is planar in both (plane-fit RMS under 2 % of the depth) at 0.8–3 m, the correlation
// of the two residual patches; the statistic is its median over patches and pairs (a pooled sum is
// led by the few patches whose residual is scene structure — a keyboard, papers — that moves with the
// view: pooled, real fr1/rpy reads 0.15 at one frame, the median 0.26).
#pragma once

#include <opencv2/core.hpp>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

namespace vobench::synth {

struct NoisePersistence {
    int gap = 0;
    double correlation = 0;   // NaN when no patch was planar in both frames of any pair
    std::size_t patches = 0;  // patch pairs measured
};

// The residuals of the patch×patch square at (x, y) about its fitted plane (fit_patch_plane), each
// divided by the plane's depth² (as disparity errors weigh), or nothing when the square is incomplete,
// not planar (RMS over 2 % of its depth) or its depth outside [near, far) metres. Also the neighbour
// correlation of `synth stats` (frame_statistics.cpp) is measured on these.
std::optional<cv::Mat> scaled_plane_residuals(const cv::Mat& depth_m, int x, int y, int patch, double near, double far);

// For each gap, up to `max_pairs` evenly spaced pairs (0: every pair). `depth_paths` in the folder's
// order; `depth_scale` units per metre. Throws std::runtime_error naming an image that cannot be read
// as 16-bit depth, or whose size differs from the first one's.
std::vector<NoisePersistence> same_pixel_noise_correlation(const std::vector<std::filesystem::path>& depth_paths,
                                                           const std::vector<int>& gaps, std::size_t max_pairs, double depth_scale);

}  // namespace vobench::synth
