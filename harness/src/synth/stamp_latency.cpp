#include "synth/stamp_latency.hpp"

#include "metrics/statistics.hpp"
#include "synth/frame_plan.hpp"

#include <tbb/parallel_for.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
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
constexpr int kReadoutSteps = 13;  // 0, 5, …, 60 ms
constexpr double kReadoutStepMs = 5.0;

struct Step {
    double total = 0;       // the per-gap medians, summed
    std::size_t pairs = 0;  // pairs that took part
    bool every_gap = true;  // false: some gap had no pair (the step does not count)
};

// A scan step's cost of the pair (i, j), NaN when the two do not overlap enough.
using StepPairCost = std::function<double(std::size_t i, std::size_t j)>;

// Costs the `count` steps of a scan in parallel, `at_step(step)` giving a step's pair cost: per gap the
// median over the pairs (i, i + gap) whose frames are both `covered`, summed over the gaps.
std::vector<Step> cost_steps(int count, const std::vector<bool>& covered, const std::function<StepPairCost(int)>& at_step) {
    std::vector<Step> steps(static_cast<std::size_t>(count));
    tbb::parallel_for(0, count, [&](int step) {
        const StepPairCost cost = at_step(step);
        Step& out = steps[static_cast<std::size_t>(step)];
        for (const int gap : kGaps) {
            std::vector<double> per_pair;
            for (std::size_t i = 0; i + static_cast<std::size_t>(gap) < covered.size(); ++i) {
                const std::size_t j = i + static_cast<std::size_t>(gap);
                if (!covered[i] || !covered[j]) continue;
                const double c = cost(i, j);
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
    return steps;
}

struct Choice {
    double value = std::numeric_limits<double>::quiet_NaN();  // first + step · size at the minimum, refined
    double cost_at_best = std::numeric_limits<double>::quiet_NaN(), cost_at_zero = std::numeric_limits<double>::quiet_NaN();
    std::size_t pairs = 0;
};

// The cheapest step in step order (the same choice, ties included, as a serial scan), refined between
// the steps by the vertex of the parabola through it and its two neighbours; `zero_step` is the step
// whose cost is reported as cost_at_zero.
Choice choose(const std::vector<Step>& steps, double first, double size, int zero_step) {
    Choice best;
    int best_step = -1;
    for (std::size_t k = 0; k < steps.size(); ++k) {
        if (!steps[k].every_gap) continue;
        if (static_cast<int>(k) == zero_step) best.cost_at_zero = steps[k].total;
        if (!(steps[k].total >= best.cost_at_best)) {  // also when cost_at_best is still NaN
            best.cost_at_best = steps[k].total;
            best.value = first + static_cast<double>(k) * size;
            best.pairs = steps[k].pairs;
            best_step = static_cast<int>(k);
        }
    }
    if (best_step > 0 && best_step + 1 < static_cast<int>(steps.size())) {
        const Step &before = steps[static_cast<std::size_t>(best_step - 1)], &after = steps[static_cast<std::size_t>(best_step + 1)];
        const double curvature = before.total - 2.0 * best.cost_at_best + after.total;
        if (before.every_gap && after.every_gap && curvature > 0) best.value += size * 0.5 * (before.total - after.total) / curvature;
    }
    return best;
}

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
    const auto steps = cost_steps(kScanSteps, covered, [&](int step) -> StepPairCost {
        const double ms = kScanFromMs + step * kScanStepMs;
        return [&, ms](std::size_t i, std::size_t j) {
            Eigen::Isometry3d pose_i, pose_j;
            interpolate_pose(reference, stamps[i] - ms * 1e-3, pose_i);
            interpolate_pose(reference, stamps[j] - ms * 1e-3, pose_j);
            return cost(i, j, pose_j.inverse() * pose_i);
        };
    });
    const Choice c = choose(steps, kScanFromMs, kScanStepMs, static_cast<int>(-kScanFromMs / kScanStepMs));
    return {c.value, c.cost_at_best, c.cost_at_zero, c.pairs};
}

// A readout scan's pair cost, given each frame's world-from-camera pose for every image row.
using RowPoses = std::vector<Eigen::Isometry3d>;
using RollingPairCost = std::function<double(std::size_t i, std::size_t j, const RowPoses& world_from_i, const RowPoses& world_from_j)>;

// Scans the readout R: row v of frame k exposed at (stamps[k] − latency) + (v / rows − 1/2)·R. Only
// frames whose every row the reference covers at the longest readout take part.
ReadoutEstimate readout_scan(const std::vector<double>& stamps, int rows, const metrics::Trajectory& reference, double latency_ms,
                             const RollingPairCost& cost) {
    ReadoutEstimate none;
    none.readout_ms = none.cost_at_best = none.cost_at_zero = std::numeric_limits<double>::quiet_NaN();
    if (stamps.empty() || rows <= 0 || !std::isfinite(latency_ms)) return none;
    const double half_longest_s = 0.5 * (kReadoutSteps - 1) * kReadoutStepMs * 1e-3;
    std::vector<bool> covered(stamps.size());
    for (std::size_t k = 0; k < stamps.size(); ++k) {
        const double middle = stamps[k] - latency_ms * 1e-3;
        Eigen::Isometry3d unused;
        covered[k] =
            interpolate_pose(reference, middle - half_longest_s, unused) && interpolate_pose(reference, middle + half_longest_s, unused);
    }
    const auto steps = cost_steps(kReadoutSteps, covered, [&](int step) -> StepPairCost {
        const double readout_s = step * kReadoutStepMs * 1e-3;
        auto row_pose = std::make_shared<std::vector<RowPoses>>(stamps.size());  // each covered frame's pose of every row
        for (std::size_t k = 0; k < stamps.size(); ++k) {
            if (!covered[k]) continue;
            RowPoses& poses = (*row_pose)[k];
            poses.resize(static_cast<std::size_t>(rows));
            for (int v = 0; v < rows; ++v)
                interpolate_pose(reference, stamps[k] - latency_ms * 1e-3 + (static_cast<double>(v) / rows - 0.5) * readout_s,
                                 poses[static_cast<std::size_t>(v)]);
        }
        return [&cost, row_pose](std::size_t i, std::size_t j) { return cost(i, j, (*row_pose)[i], (*row_pose)[j]); };
    });
    const Choice c = choose(steps, 0.0, kReadoutStepMs, 0);
    return {c.value, c.cost_at_best, c.cost_at_zero, c.pairs};
}

// A colour frame's textured pixels with depth: their points in the camera frame and blurred grey levels.
struct ColorSamples {
    std::vector<cv::Point3f> points;
    std::vector<float> grey;
    std::vector<int> rows;  // the image row each was seen on
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
            s.rows.push_back(v);
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

ReadoutEstimate color_readout(const LatencyFrames& frames, const metrics::Trajectory& reference, const DepthRays& rays, double latency_ms) {
    if (frames.grey.empty()) return readout_scan({}, 0, reference, latency_ms, nullptr);
    const int rows = frames.grey.front().rows;
    std::vector<cv::Mat> images;
    std::vector<ColorSamples> samples;
    for (std::size_t k = 0; k < frames.stamps.size(); ++k) {
        images.push_back(blurred(frames.grey[k]));
        samples.push_back(color_samples(images.back(), frames.depth_m[k], rays));
    }
    return readout_scan(
        frames.stamps, rows, reference, latency_ms, [&](std::size_t i, std::size_t j, const RowPoses& pi, const RowPoses& pj) {
            // Each point into the world at its own row's pose, then into frame j as its rolling shutter sees it.
            const ColorSamples& from = samples[i];
            std::vector<Eigen::Vector3d> world;
            std::vector<float> grey;
            const Eigen::Isometry3d j_middle_from_world = pj[pj.size() / 2].inverse();
            for (std::size_t k = 0; k < from.points.size(); ++k) {
                const Eigen::Vector3d w =
                    pi[static_cast<std::size_t>(from.rows[k])] * Eigen::Vector3d(from.points[k].x, from.points[k].y, from.points[k].z);
                if ((j_middle_from_world * w).z() <= 0.05) continue;
                world.push_back(w);
                grey.push_back(from.grey[k]);
            }
            const std::vector<cv::Point3f> seen = into_rolling_camera(world, pj, rays);
            const auto pixels = rays.project(seen);
            std::vector<double> differences;
            for (std::size_t k = 0; k < pixels.size(); ++k) {
                double there = 0;
                if (bilinear(images[j], pixels[k].x, pixels[k].y, there)) differences.push_back(std::abs(there - grey[k]));
            }
            return differences.size() < kMinColorPoints ? std::numeric_limits<double>::quiet_NaN()
                                                        : metrics::compute_stats(differences).median;
        });
}

ReadoutEstimate depth_readout(const LatencyFrames& frames, const metrics::Trajectory& reference, const DepthRays& rays, double latency_ms) {
    const int rows = frames.depth_m.empty() ? 0 : frames.depth_m.front().rows;
    return readout_scan(
        frames.stamps, rows, reference, latency_ms, [&](std::size_t i, std::size_t j, const RowPoses& pi, const RowPoses& pj) {
            return 100.0 *
                   median_pair_residual(depth_pair_residuals_rolling(frames.depth_m[i], frames.depth_m[j], pi, pj, rays, kDepthStridePx));
        });
}

}  // namespace vobench::synth
