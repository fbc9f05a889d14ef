// track_precision.hpp — how precisely a small-window Lucas–Kanade tracker follows corners from one
// frame into the next: the forward–backward distance (Kalal et al. 2010) of Shi–Tomasi corners tracked
// with a 7×7 window over three pyramid levels (the window of PUT's VO, Kraft et al. 2016) and back.
// Noise, blur and texture all set it, as they set what a feature-based VO gets from the images; a
// rendering whose frames track more precisely than the real camera's is easier than reality
// (issue #15; `vobench synth stats`).
#pragma once

#include <opencv2/core.hpp>

#include <optional>

namespace vobench::synth {

// The median forward–backward distance, px, over the corners of `a` tracked into `b` and back, or
// nothing when fewer than 20 corners could be tracked both ways. Both images 8-bit grey and of one size,
// else std::invalid_argument.
std::optional<double> forward_backward_median_px(const cv::Mat& a, const cv::Mat& b);

}  // namespace vobench::synth
