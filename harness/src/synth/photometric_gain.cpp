#include "synth/photometric_gain.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vobench::synth {
namespace {

constexpr int kMaxCorners = 400;
constexpr int kMeanWindow = 7;  // the brightness compared: a 7×7 mean, so that noise and a sub-pixel
                                // tracking error hardly move it
constexpr std::size_t kMinCorners = 20;

// sRGB (IEC 61966-2-1) decoded to linear light, per grey level: a table for cv::LUT.
const cv::Mat& srgb_to_linear() {
    static const cv::Mat table = [] {
        cv::Mat t(1, 256, CV_32F);
        for (int i = 0; i < 256; ++i) {
            const double c = i / 255.0;
            t.at<float>(0, i) = static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table;
}

cv::Mat linear_light(const cv::Mat& grey) {
    cv::Mat linear;
    cv::LUT(grey, srgb_to_linear(), linear);
    return linear;
}

// Pearson correlation of `values` with the frames' median depth, over the frames that have one.
double correlation_with_depth(const std::vector<ExposureFrame>& frames, const std::vector<double>& values) {
    double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const double x = frames[k].median_depth_m, y = values[k];
        if (!std::isfinite(x)) continue;
        n += 1;
        sx += x;
        sy += y;
        sxx += x * x;
        syy += y * y;
        sxy += x * y;
    }
    const double vx = sxx - sx * sx / n, vy = syy - sy * sy / n;
    if (n < 10 || vx <= 0 || vy <= 0) return std::numeric_limits<double>::quiet_NaN();
    return (sxy - sx * sy / n) / std::sqrt(vx * vy);
}

}  // namespace

GainFrame prepare_gain_frame(const cv::Mat& grey) {
    if (grey.type() != CV_8UC1) throw std::invalid_argument("prepare_gain_frame: an 8-bit grey image expected");
    const cv::Size window(kMeanWindow, kMeanWindow);
    GainFrame f;
    f.grey = grey;
    const cv::Mat linear = linear_light(grey);
    f.mean_linear_light = cv::mean(linear)[0];
    cv::blur(linear, f.mean_linear, window);
    grey.convertTo(f.mean_grey, CV_32F);
    cv::blur(f.mean_grey, f.mean_grey, window);
    return f;
}

std::optional<GainChange> measure_gain_change(const GainFrame& a, const GainFrame& b) {
    if (a.grey.size() != b.grey.size()) throw std::invalid_argument("measure_gain_change: two images of one size expected");
    std::vector<cv::Point2f> from;
    cv::goodFeaturesToTrack(a.grey, from, kMaxCorners, 0.01, 8);
    if (from.size() < kMinCorners) return std::nullopt;
    std::vector<cv::Point2f> to;
    std::vector<unsigned char> tracked;
    std::vector<float> error;
    cv::calcOpticalFlowPyrLK(a.grey, b.grey, from, to, tracked, error, cv::Size(21, 21), 3);

    const int margin = kMeanWindow / 2 + 1;
    auto inside = [&](cv::Point p) { return p.x >= margin && p.y >= margin && p.x < a.grey.cols - margin && p.y < a.grey.rows - margin; };
    auto usable = [](float grey) { return grey > 20.0f && grey < 235.0f; };
    std::vector<double> ratios;
    for (std::size_t i = 0; i < from.size(); ++i) {
        if (!tracked[i]) continue;
        const cv::Point p(cvRound(from[i].x), cvRound(from[i].y)), q(cvRound(to[i].x), cvRound(to[i].y));
        if (!inside(p) || !inside(q)) continue;
        if (!usable(a.mean_grey.at<float>(p)) || !usable(b.mean_grey.at<float>(q))) continue;
        ratios.push_back(std::log(static_cast<double>(b.mean_linear.at<float>(q)) / a.mean_linear.at<float>(p)));
    }
    if (ratios.size() < kMinCorners) return std::nullopt;
    const auto middle = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
    std::nth_element(ratios.begin(), middle, ratios.end());
    return GainChange{*middle, ratios.size()};
}

std::optional<ExposureFit> fit_exposure_time_constant(const std::vector<ExposureFrame>& frames) {
    constexpr std::size_t kMinFrames = 10;
    if (frames.size() < kMinFrames) return std::nullopt;
    const std::size_t n = frames.size();
    std::vector<double> log_gain(n, 0.0), scene(n);  // G_k, and L_k = observed / gain
    for (std::size_t k = 0; k < n; ++k) {
        if (k > 0) log_gain[k] = log_gain[k - 1] + frames[k].log_gain;
        scene[k] = std::max(frames[k].mean_linear, 1e-6) / std::exp(log_gain[k]);
    }
    auto rms_about_mean = [](const std::vector<double>& r) {
        double mean = 0, ss = 0;
        for (double x : r) mean += x;
        mean /= static_cast<double>(r.size());
        for (double x : r) ss += (x - mean) * (x - mean);
        return std::sqrt(ss / static_cast<double>(r.size()));
    };
    ExposureFit best;
    best.rms = std::numeric_limits<double>::infinity();
    best.rms_of_gain = rms_about_mean(log_gain);
    std::vector<double> log_scene(n);
    for (std::size_t k = 0; k < n; ++k) log_scene[k] = std::log(scene[k]);
    best.scene_log_sd = rms_about_mean(log_scene);
    best.scene_depth_correlation = correlation_with_depth(frames, log_scene);
    std::vector<double> residual(n);
    for (int step = 0; step <= 35; ++step) {  // 10 ms · 2^(step/4): 10 ms to 4.2 s
        const double tau = 0.01 * std::pow(2.0, step / 4.0);
        if (tau > 3.0) break;
        double reference = scene[0];
        for (std::size_t k = 0; k < n; ++k) {
            if (k > 0) {
                const double dt = std::abs(frames[k].stamp - frames[k - 1].stamp);
                reference += (1.0 - std::exp(-dt / tau)) * (scene[k - 1] - reference);
            }
            residual[k] = log_gain[k] + std::log(reference);
        }
        const double rms = rms_about_mean(residual);
        if (rms < best.rms) {
            best.rms = rms;
            best.time_constant_s = tau;
        }
    }
    return best;
}

}  // namespace vobench::synth
