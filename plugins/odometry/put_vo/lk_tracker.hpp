// lk_tracker.hpp — cv::calcOpticalFlowPyrLK's pyramidal Lucas–Kanade (Bouguet 2000), bit for bit,
// faster for windows narrower than 8 px.
//
// Why: OpenCV 4.6 runs its SIMD loop over whole groups of 8 pixels of a window row only; a 7-px row
// (the paper's window, put_vo's `lk_window`) goes through its scalar loop, pixel by pixel — measured
// on the real fr1/rpy frames, an 8-px window tracks the same points 2.6× faster than a 7-px one.
// Here a narrow row's pixels are interpolated and multiplied in one 8-lane group (integer arithmetic,
// exact), and only the float sums are taken one pixel after another, in OpenCV's order, so that
// positions and status are OpenCV's to the bit (tests/plugins/lk_tracker_test.cpp holds them
// against cv::calcOpticalFlowPyrLK). Windows 8 px or wider go to OpenCV itself.
// With integer_sums the window sums are kept in exact integer lanes instead (not OpenCV's rounding;
// 1.66 → 1.20 ms for 400 real corners, bench/odometry_bench.cpp run_lucas_kanade).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace put_vo {

struct LkOptions {
    cv::Size window{7, 7};          // the LK window, px (any size from 3)
    int levels = 2;                 // pyramid levels above the base
    int max_iterations = 30;        // per level (OpenCV clamps to 0..100; so does this)
    double epsilon = 0.01;          // stop when a step is shorter, px
    bool use_initial_flow = false;  // `to` holds each search's starting point (OPTFLOW_USE_INITIAL_FLOW)
    double min_eigen = 1e-4;        // OpenCV's default minEigThreshold: a window too flat to track fails
    // The window sums (structure tensor, Gauss–Newton right-hand side) in 32-bit integer lanes, exact,
    // instead of OpenCV's float additions one pixel after another: no longer OpenCV's result to the
    // bit (positions differ by float rounding, ~1e-5 px), but the sums' dependency chain is gone.
    // Windows of more than 64 px always take OpenCV's order (the integer sums could overflow).
    bool integer_sums = false;
};

// The border, px, the pyramids given to track_lk must have on every side: a narrow row is read as a
// whole 8-px group, and one pixel more for the bilinear weights.
int lk_pyramid_border(cv::Size window);

// Tracks `from` (pixels of the previous image) into the next image; `to` receives the positions
// (and, with use_initial_flow, gives the starting points), `status` 1 where the track held.
// `previous` and `next` are cv::buildOpticalFlowPyramid's output with derivatives ([image, Scharr
// derivative] per level, at least options.levels + 1 levels), built with a border of at least
// lk_pyramid_border(options.window); only `previous`'s derivatives are read. Single-threaded.
void track_lk(const std::vector<cv::Mat>& previous, const std::vector<cv::Mat>& next, const std::vector<cv::Point2f>& from,
              std::vector<cv::Point2f>& to, std::vector<unsigned char>& status, const LkOptions& options);

}  // namespace put_vo
