#include "synth/track_precision.hpp"

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace vobench::synth {

namespace {
constexpr int kMaxCorners = 400, kMinCorners = 20, kWindow = 7, kLevels = 2;
}

std::optional<double> forward_backward_median_px(const cv::Mat& a, const cv::Mat& b) {
    if (a.type() != CV_8UC1 || b.type() != CV_8UC1 || a.size() != b.size())
        throw std::invalid_argument("forward_backward_median_px: two 8-bit grey images of one size expected");
    std::vector<cv::Point2f> from;
    cv::goodFeaturesToTrack(a, from, kMaxCorners, 0.01, 8);
    if (from.size() < static_cast<std::size_t>(kMinCorners)) return std::nullopt;
    std::vector<cv::Point2f> to, back;
    std::vector<unsigned char> ok, back_ok;
    std::vector<float> error;
    const cv::Size window(kWindow, kWindow);
    cv::calcOpticalFlowPyrLK(a, b, from, to, ok, error, window, kLevels);
    cv::calcOpticalFlowPyrLK(b, a, to, back, back_ok, error, window, kLevels);
    std::vector<double> distances;
    const cv::Rect image(0, 0, a.cols, a.rows);
    for (std::size_t i = 0; i < from.size(); ++i)
        if (ok[i] && back_ok[i] && image.contains(cv::Point(cvFloor(to[i].x), cvFloor(to[i].y))))
            distances.push_back(cv::norm(back[i] - from[i]));
    if (distances.size() < static_cast<std::size_t>(kMinCorners)) return std::nullopt;
    const auto middle = distances.begin() + static_cast<std::ptrdiff_t>(distances.size() / 2);
    std::nth_element(distances.begin(), middle, distances.end());
    return *middle;
}

}  // namespace vobench::synth
