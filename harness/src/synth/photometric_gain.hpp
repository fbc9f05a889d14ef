// photometric_gain.hpp — how much the colour camera's brightness jumps from one frame to the next, a
// statistic of `vobench synth stats` (issue #15).
//
// Auto-exposure and gain change every pixel's value by a common factor between frames. Methods that
// assume brightness constancy (Lucas–Kanade tracking, the photometric term of dense RGB-D odometry)
// read such a change as motion; descriptor matching hardly notices it. The change is measured where the
// scene is the same in both frames: Shi–Tomasi corners of frame a tracked into frame b (pyramidal LK,
// 21×21, 3 levels), the 7×7 mean around each in linear light (sRGB decoded, so a gain is a ratio),
// and the median over the corners of log(b / a). Corners whose mean is near black or near clipping
// (grey ≤ 20 or ≥ 235) in either frame are left out: there the ratio is not the gain. The median
// ignores what moves differently from the gain — specular highlights, vignetting under a moving
// feature, occlusions. A rendering knows its gains; the test checks the estimate against them.
#pragma once

#include <opencv2/core.hpp>

#include <limits>
#include <optional>
#include <vector>

namespace vobench::synth {

struct GainChange {
    double log_ratio = 0;     // median log(b / a) of the corners' linear brightness
    std::size_t corners = 0;  // corners it is the median of
};

// A frame prepared once for the two comparisons it takes part in (the later frame of one pair, the
// earlier of the next): the grey image and its 7×7 means, in grey levels and in linear light.
struct GainFrame {
    cv::Mat grey;                  // 8-bit sRGB, shared with the caller's image
    cv::Mat mean_grey;             // CV_32F
    cv::Mat mean_linear;           // CV_32F
    double mean_linear_light = 0;  // of the whole image (the exposure fit's observed mean)
};
// Throws std::invalid_argument unless `grey` is an 8-bit single-channel image.
GainFrame prepare_gain_frame(const cv::Mat& grey);

// The common brightness change from frame `a` to frame `b` (same size, else std::invalid_argument),
// or nothing when fewer than 20 corners could be tracked and compared (a blank or saturated view).
std::optional<GainChange> measure_gain_change(const GainFrame& a, const GainFrame& b);
inline std::optional<GainChange> measure_gain_change(const cv::Mat& a, const cv::Mat& b) {
    return measure_gain_change(prepare_gain_frame(a), prepare_gain_frame(b));
}

// The time constant of the renderer's auto-exposure model that best explains a run of consecutive
// frames (sequence_writer.cpp: frame k's gain is target / r_k, r a first-order average of the earlier
// frames' scene luminance, r_k = r_{k-1} + (1 − e^(−Δt/τ)) (L_{k-1} − r_{k-1})). The gains G_k are the
// measured changes summed; the scene luminance L_k = observed mean / gain. τ minimises the RMS of
// log G_k + log r_k about its mean over 10 ms – 3 s (a grid of 2^(1/4) steps). Checked on renderings,
// whose τ is known: `docs/synthetic-sensors.md`, auto-exposure.
struct ExposureFit {
    double time_constant_s = 0;
    double rms = 0;           // of the log gain about the model's, at the best τ
    double rms_of_gain = 0;   // of the log gain itself: how much there was to explain
    double scene_log_sd = 0;  // of log L_k: how much the scene's brightness varies over the views
    // Pearson correlation of log L_k with the frames' median depth over the frames that have one
    // (NaN for fewer than 10): whether far views are the dark or the bright ones.
    double scene_depth_correlation = 0;
};
struct ExposureFrame {
    double stamp = 0;        // seconds
    double mean_linear = 0;  // GainFrame::mean_linear_light
    double log_gain = 0;     // measured log brightness change from the frame before (ignored on the first)
    double median_depth_m = std::numeric_limits<double>::quiet_NaN();  // of the frame's valid depth, if any
};
// Nothing for fewer than 10 frames.
std::optional<ExposureFit> fit_exposure_time_constant(const std::vector<ExposureFrame>& frames);

}  // namespace vobench::synth
