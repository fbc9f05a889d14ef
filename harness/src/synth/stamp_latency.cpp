#include "synth/stamp_latency.hpp"

#include "metrics/statistics.hpp"
#include "synth/frame_plan.hpp"

#include <tbb/parallel_for.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace vobench::synth {
namespace {

constexpr int kGaps[] = {1, 2, 4};
constexpr int kScanSteps = 26;  // −10, −8, …, 40 ms
constexpr double kScanFromMs = -10.0, kScanStepMs = 2.0;
constexpr int kDepthStridePx = 8;
constexpr int kColorStridePx = 4;
constexpr float kMinGradient = 20.0f;  // Sobel magnitude of the blurred grey image (grey levels · 4)
constexpr std::size_t kMinColorPoints = 200;

// A pair's cost under the relative motion `j_from_i`, NaN when the two do not overlap enough.
using PairCost = std::function<double(std::size_t i, std::size_t j, const Eigen::Isometry3d& j_from_i)>;

// Scans the latency; only pairs the reference covers at every latency of the scan take part, so that
// every step sums the same pairs.
LatencyEstimate scan(const std::vector<double>& stamps, const metrics::Trajectory& reference, const PairCost& cost) {
    const double last_ms = kScanFromMs + (kScanSteps - 1) * kScanStepMs;
    std::vector<bool> covered(stamps.size());
    for (std::size_t k = 0; k < stamps.size(); ++k) {
        Eigen::Isometry3d unused;
        covered[k] = interpolate_pose(reference, stamps[k] - kScanFromMs * 1e-3, unused) &&
                     interpolate_pose(reference, stamps[k] - last_ms * 1e-3, unused);
    }
    // The steps are independent: cost them in parallel, then choose in step order (the same choice,
    // ties included, as a serial scan).
    struct Step {
        double total = 0;
        std::size_t pairs = 0;
        bool every_gap = true;
    };
    std::vector<Step> steps(kScanSteps);
    tbb::parallel_for(0, kScanSteps, [&](int step) {
        const double ms = kScanFromMs + step * kScanStepMs;
        Step& out = steps[static_cast<std::size_t>(step)];
        for (const int gap : kGaps) {
            std::vector<double> per_pair;
            for (std::size_t i = 0; i + static_cast<std::size_t>(gap) < stamps.size(); ++i) {
                const std::size_t j = i + static_cast<std::size_t>(gap);
                if (!covered[i] || !covered[j]) continue;
                Eigen::Isometry3d pose_i, pose_j;
                interpolate_pose(reference, stamps[i] - ms * 1e-3, pose_i);
                interpolate_pose(reference, stamps[j] - ms * 1e-3, pose_j);
                const double c = cost(i, j, pose_j.inverse() * pose_i);
                if (std::isfinite(c)) per_pair.push_back(c);
            }
            if (per_pair.empty()) {
                out.every_gap = false;
                return;
            }
            out.total += metrics::compute_stats(per_pair).median;
            out.pairs += per_pair.size();
        }
    });
    LatencyEstimate best;
    best.latency_ms = best.cost_at_best = best.cost_at_zero = std::numeric_limits<double>::quiet_NaN();
    for (int step = 0; step < kScanSteps; ++step) {
        const Step& s = steps[static_cast<std::size_t>(step)];
        if (!s.every_gap) continue;
        if (step * kScanStepMs == -kScanFromMs) best.cost_at_zero = s.total;
        if (!(s.total >= best.cost_at_best)) {  // also when cost_at_best is still NaN
            best.cost_at_best = s.total;
            best.latency_ms = kScanFromMs + step * kScanStepMs;
            best.pairs = s.pairs;
        }
    }
    return best;
}

// A colour frame's textured pixels with depth: their points in the camera frame and blurred grey levels.
struct ColorSamples {
    std::vector<cv::Point3f> points;
    std::vector<float> grey;
};

cv::Mat blurred(const cv::Mat& grey) {
    cv::Mat f, out;
    grey.convertTo(f, CV_32F);
    cv::GaussianBlur(f, out, cv::Size(5, 5), 1.0);
    return out;
}

ColorSamples color_samples(const cv::Mat& blurred_grey, const cv::Mat& depth_m, const DepthRays& rays) {
    cv::Mat gx, gy;
    cv::Sobel(blurred_grey, gx, CV_32F, 1, 0);
    cv::Sobel(blurred_grey, gy, CV_32F, 0, 1);
    ColorSamples s;
    for (int v = 0; v < depth_m.rows; v += kColorStridePx)
        for (int u = 0; u < depth_m.cols; u += kColorStridePx) {
            const float z = depth_m.at<float>(v, u);
            if (z <= 0 || std::hypot(gx.at<float>(v, u), gy.at<float>(v, u)) <= kMinGradient) continue;
            const Eigen::Vector3d p = rays.point(u, v, z);
            s.points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
            s.grey.push_back(blurred_grey.at<float>(v, u));
        }
    return s;
}

bool bilinear(const cv::Mat& image, float u, float v, double& out) {
    const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
    if (u0 < 0 || v0 < 0 || u0 + 1 >= image.cols || v0 + 1 >= image.rows) return false;
    const double a = u - u0, b = v - v0;
    out = (1 - a) * (1 - b) * image.at<float>(v0, u0) + a * (1 - b) * image.at<float>(v0, u0 + 1) +
          (1 - a) * b * image.at<float>(v0 + 1, u0) + a * b * image.at<float>(v0 + 1, u0 + 1);
    return true;
}

}  // namespace

LatencyEstimate depth_latency(const LatencyFrames& frames, const metrics::Trajectory& reference, const DepthRays& rays) {
    return scan(frames.stamps, reference, [&](std::size_t i, std::size_t j, const Eigen::Isometry3d& j_from_i) {
        return 100.0 * depth_pair_residual(frames.depth_m[i], frames.depth_m[j], j_from_i, rays, kDepthStridePx);
    });
}

LatencyEstimate color_latency(const LatencyFrames& frames, const metrics::Trajectory& reference, const DepthRays& rays) {
    std::vector<cv::Mat> images;
    std::vector<ColorSamples> samples;
    for (std::size_t k = 0; k < frames.stamps.size(); ++k) {
        images.push_back(blurred(frames.grey[k]));
        samples.push_back(color_samples(images.back(), frames.depth_m[k], rays));
    }
    return scan(frames.stamps, reference, [&](std::size_t i, std::size_t j, const Eigen::Isometry3d& j_from_i) {
        const ColorSamples& from = samples[i];
        std::vector<cv::Point3f> moved;
        std::vector<float> grey;
        for (std::size_t k = 0; k < from.points.size(); ++k) {
            const Eigen::Vector3d q = j_from_i * Eigen::Vector3d(from.points[k].x, from.points[k].y, from.points[k].z);
            if (q.z() <= 0.05) continue;
            moved.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()));
            grey.push_back(from.grey[k]);
        }
        const auto pixels = rays.project(moved);
        std::vector<double> differences;
        for (std::size_t k = 0; k < pixels.size(); ++k) {
            double there = 0;
            if (bilinear(images[j], pixels[k].x, pixels[k].y, there)) differences.push_back(std::abs(there - grey[k]));
        }
        return differences.size() < kMinColorPoints ? std::numeric_limits<double>::quiet_NaN() : metrics::compute_stats(differences).median;
    });
}

}  // namespace vobench::synth
