#include "synth/disparity_distortion_fit.hpp"

#include "metrics/statistics.hpp"
#include "metrics/trajectory_io.hpp"
#include "synth/camera_clock.hpp"
#include "synth/frame_plan.hpp"
#include "synth/rotation_vector.hpp"
#include "tum_lists.hpp"  // plugins/common
#include "util/files.hpp"

#include <tbb/parallel_for.h>
#include <Eigen/Dense>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace vobench::synth {
namespace {

constexpr int kStridePx = 8;
constexpr int kFitGaps[] = {4, 16};
constexpr double kFloor = 0.005;            // IRLS weight 1 / max(|r|, this): an L1-like cost
constexpr double kStep = 1e-3;              // forward-difference step, px
constexpr std::size_t kMinResiduals = 600;  // below this, three coefficients are not pinned down

constexpr double kLatencyRangeS = 0.05;  // a free latency stays within this of its start
constexpr double kLatencyStepS = 5e-4;   // forward-difference steps of the latency, s …
constexpr double kTurnStepRad = 1e-4;    // … and of the turn, rad

// The reference's side of the model: the latency of the depth stamps and the turn of its frame.
struct ReferenceModel {
    double latency_s = 0;
    Eigen::Vector3d turn_rad = Eigen::Vector3d::Zero();
};

struct Pair {
    std::size_t i, j;
};

// Pairs (i, i + gap) whose depth stamps, less any latency within ±`margin_s` of `latency_s`, the reference covers.
std::vector<Pair> covered_pairs(const DepthSequence& s, const std::vector<int>& gaps, std::size_t step, double latency_s, double margin_s) {
    const auto covered = [&](double stamp) {
        Eigen::Isometry3d pose;
        return interpolate_pose(s.reference, stamp - latency_s - margin_s, pose) &&
               interpolate_pose(s.reference, stamp - latency_s + margin_s, pose);
    };
    std::vector<Pair> out;
    for (const int gap : gaps)
        for (std::size_t i = 0; i + static_cast<std::size_t>(gap) < s.stamps.size(); i += step) {
            const std::size_t j = i + static_cast<std::size_t>(gap);
            if (covered(s.stamps[i]) && covered(s.stamps[j])) out.push_back({i, j});
        }
    return out;
}

// The camera's motion from frame i to frame j under the model: X·(G_j⁻¹·G_i)·X⁻¹, G at the stamps less the latency.
Eigen::Isometry3d camera_j_from_i(const DepthSequence& s, const Pair& p, const ReferenceModel& model) {
    Eigen::Isometry3d pose_i, pose_j;
    interpolate_pose(s.reference, s.stamps[p.i] - model.latency_s, pose_i);  // covered_pairs checked both
    interpolate_pose(s.reference, s.stamps[p.j] - model.latency_s, pose_j);
    const Eigen::Isometry3d turn(exp_rotation(model.turn_rad));
    return turn * pose_j.inverse() * pose_i * turn.inverse();
}

std::vector<cv::Mat> corrected_images(const DepthSequence& s, const PinholeCamera& camera, const DisparityOffset& delta,
                                      double focal_baseline) {
    std::vector<cv::Mat> out(s.depth_m.size());
    tbb::parallel_for(std::size_t{0}, out.size(),
                      [&](std::size_t k) { out[k] = undo_disparity_offset(s.depth_m[k], camera, delta, focal_baseline); });
    return out;
}

// Every pair's residuals, concatenated in pair order (the same slots for every offset and model).
std::vector<double> all_residuals(const DepthSequence& s, const DepthRays& rays, const std::vector<Pair>& pairs,
                                  const std::vector<cv::Mat>& images, const ReferenceModel& model) {
    std::vector<std::vector<double>> per_pair(pairs.size());
    tbb::parallel_for(std::size_t{0}, pairs.size(), [&](std::size_t p) {
        per_pair[p] =
            depth_pair_residuals(images[pairs[p].i], images[pairs[p].j], camera_j_from_i(s, pairs[p], model), rays, kStridePx).relative;
    });
    std::vector<double> out;
    for (const auto& r : per_pair) out.insert(out.end(), r.begin(), r.end());
    return out;
}

// The parameters in one vector: a, b, c (px), the latency (s), the turn (rad); `free` says which move.
using Parameters = Eigen::Matrix<double, 7, 1>;
constexpr double kParameterStep[7] = {kStep, kStep, kStep, kLatencyStepS, kTurnStepRad, kTurnStepRad, kTurnStepRad};

DisparityOffset offset_of(const Parameters& p) { return {p[0], p[1], p[2]}; }
ReferenceModel model_of(const Parameters& p) { return {p[3], p.segment<3>(4)}; }

// A list's entries, each checked to name a file inside the folder (the copy writes to the same relative path).
std::vector<tum::ListEntry> contained_list(const std::filesystem::path& list_file) {
    std::vector<tum::ListEntry> list = tum::parse_list(read_file(list_file), list_file.string());
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::filesystem::path p(list[k].path);
        bool escapes = p.is_absolute() || p.has_root_name() || p.empty();
        for (const auto& part : p) escapes = escapes || part == "..";
        if (escapes)
            throw std::runtime_error(list_file.string() + ": entry " + std::to_string(k + 1) + " ('" + list[k].path +
                                     "') is not a path inside the folder");
    }
    return list;
}

}  // namespace

DepthSequence read_depth_sequence(const std::filesystem::path& folder, const PinholeCamera& camera, double depth_scale,
                                  std::size_t max_frames) {
    DepthSequence s;
    auto list = tum::parse_list(read_file(folder / "depth.txt"), (folder / "depth.txt").string());
    if (max_frames > 0 && list.size() > max_frames) list.resize(max_frames);
    for (const auto& e : list) {
        cv::Mat depth = read_depth_metres(folder / e.path, depth_scale);
        require_camera_size(folder / e.path, depth, camera);
        s.stamps.push_back(e.stamp);
        s.depth_m.push_back(std::move(depth));
    }
    s.stamps = fit_camera_clock(s.stamps).ticks;  // the images were taken on the clock (camera_clock.hpp)
    s.reference = metrics::read_trajectory(folder / "groundtruth.txt").poses;
    return s;
}

cv::Mat undo_disparity_offset(const cv::Mat& depth_m, const PinholeCamera& camera, const DisparityOffset& delta, double focal_baseline) {
    cv::Mat out(depth_m.size(), CV_32FC1);
    for (int v = 0; v < depth_m.rows; ++v) {
        const double y = (v - camera.cy) / camera.fy;
        for (int u = 0; u < depth_m.cols; ++u) {
            const float z = depth_m.at<float>(v, u);
            const double x = (u - camera.cx) / camera.fx;
            const double d = z > 0 ? focal_baseline / z - (delta[0] * (x * x + y * y) + delta[1] * x + delta[2] * y) : 0.0;
            out.at<float>(v, u) = d > 0 ? static_cast<float>(focal_baseline / d) : 0.0f;
        }
    }
    return out;
}

DistortionFit fit_disparity_distortion(const DepthSequence& sequence, const DepthRays& rays, const DistortionFitOptions& options) {
    const double start_latency = options.depth_latency_s;
    if (!std::isfinite(start_latency) || !options.reference_turn_rad.allFinite())
        throw std::runtime_error("fit-distortion: the depth latency and the reference's turn must be finite numbers");
    const std::vector<Pair> pairs = covered_pairs(sequence, std::vector<int>(std::begin(kFitGaps), std::end(kFitGaps)), 2, start_latency,
                                                  options.fit_latency ? kLatencyRangeS : 0.0);
    if (pairs.empty()) throw std::runtime_error("fit-distortion: the reference covers no pair of depth frames 4 or 16 apart");
    std::vector<int> free = {0, 1, 2};
    if (options.fit_latency) free.push_back(3);
    if (options.fit_reference_turn) free.insert(free.end(), {4, 5, 6});
    const auto n = static_cast<Eigen::Index>(free.size());
    Parameters p;
    p << 0, 0, 0, start_latency, options.reference_turn_rad;
    DistortionFit fit;
    fit.pairs = pairs.size();
    for (int it = 0; it < options.iterations; ++it) {
        const std::vector<cv::Mat> images = corrected_images(sequence, rays.camera(), offset_of(p), options.focal_baseline_px_m);
        const std::vector<double> r0 = all_residuals(sequence, rays, pairs, images, model_of(p));
        std::vector<std::vector<double>> moved;
        for (const int c : free) {
            Parameters q = p;
            q[c] += kParameterStep[c];
            // Only the field changes the images; the latency and the turn change the motions alone.
            moved.push_back(c < 3 ? all_residuals(sequence, rays, pairs,
                                                  corrected_images(sequence, rays.camera(), offset_of(q), options.focal_baseline_px_m),
                                                  model_of(q))
                                  : all_residuals(sequence, rays, pairs, images, model_of(q)));
        }
        Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(n, n);
        Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n), J(n);
        std::size_t used = 0;
        for (std::size_t k = 0; k < r0.size(); ++k) {
            const double r = r0[k];
            if (!std::isfinite(r) || std::abs(r) > kOcclusionResidual) continue;
            bool finite = true;
            for (Eigen::Index c = 0; c < n; ++c) {
                J[c] = (moved[static_cast<std::size_t>(c)][k] - r) / kParameterStep[free[static_cast<std::size_t>(c)]];
                finite = finite && std::isfinite(J[c]);
            }
            if (!finite) continue;
            const double w = 1.0 / std::max(std::abs(r), kFloor);
            normal += w * J * J.transpose();
            rhs += w * J * r;
            ++used;
        }
        const Eigen::FullPivLU<Eigen::MatrixXd> lu(normal);
        if (used < kMinResiduals || !lu.isInvertible())
            throw std::runtime_error("fit-distortion: too few depth residuals (" + std::to_string(used) + ") to fit " + std::to_string(n) +
                                     " parameters");
        const Eigen::VectorXd step = lu.solve(rhs);
        for (Eigen::Index c = 0; c < n; ++c) p[free[static_cast<std::size_t>(c)]] -= step[c];
        p[3] = std::clamp(p[3], start_latency - kLatencyRangeS, start_latency + kLatencyRangeS);
        fit.residuals = used;
    }
    fit.delta = offset_of(p);
    fit.depth_latency_s = p[3];
    fit.reference_turn_rad = p.segment<3>(4);
    return fit;
}

double corrected_residual_pct(const DepthSequence& sequence, const DepthRays& rays, int gap, const DisparityOffset& delta,
                              const DistortionFitOptions& options, std::size_t& pairs) {
    const std::vector<Pair> chosen = covered_pairs(sequence, {gap}, 1, options.depth_latency_s, 0.0);
    const std::vector<cv::Mat> images = corrected_images(sequence, rays.camera(), delta, options.focal_baseline_px_m);
    const ReferenceModel model{options.depth_latency_s, options.reference_turn_rad};
    std::vector<double> per_pair(chosen.size(), std::numeric_limits<double>::quiet_NaN());
    tbb::parallel_for(std::size_t{0}, chosen.size(), [&](std::size_t p) {
        per_pair[p] =
            depth_pair_residual(images[chosen[p].i], images[chosen[p].j], camera_j_from_i(sequence, chosen[p], model), rays, kStridePx);
    });
    std::vector<double> finite;
    for (const double r : per_pair)
        if (std::isfinite(r)) finite.push_back(100.0 * r);
    pairs = finite.size();
    return finite.empty() ? std::numeric_limits<double>::quiet_NaN() : metrics::compute_stats(finite).median;
}

std::size_t write_corrected_folder(const std::filesystem::path& in, const std::filesystem::path& out, const PinholeCamera& camera,
                                   const DisparityOffset& delta, double focal_baseline_px_m, double depth_scale) {
    namespace fs = std::filesystem;
    if (fs::exists(out) && (!fs::is_directory(out) || !fs::is_empty(out)))
        throw std::runtime_error(out.string() + ": exists and is not an empty folder; the corrected copy needs a new one");
    const std::vector<tum::ListEntry> depth = contained_list(in / "depth.txt");
    const std::vector<tum::ListEntry> rgb = fs::exists(in / "rgb.txt") ? contained_list(in / "rgb.txt") : std::vector<tum::ListEntry>{};
    fs::create_directories(out);
    for (const char* name : {"rgb.txt", "depth.txt", "groundtruth.txt"})
        if (fs::exists(in / name)) fs::copy_file(in / name, out / name);
    for (const auto& e : rgb) {
        if (!fs::is_regular_file(in / e.path)) throw std::runtime_error((in / e.path).string() + ": listed in rgb.txt, not a file");
        fs::create_directories((out / e.path).parent_path());
        fs::copy_file(in / e.path, out / e.path, fs::copy_options::skip_existing);
    }
    for (const auto& e : depth) {
        const cv::Mat measured = read_depth_metres(in / e.path, depth_scale);
        require_camera_size(in / e.path, measured, camera);
        cv::Mat corrected = undo_disparity_offset(measured, camera, delta, focal_baseline_px_m), units;
        corrected.setTo(0, corrected > 65535.0 / depth_scale);  // beyond what the format holds: no measurement, not a clipped one
        corrected.convertTo(units, CV_16UC1, depth_scale);      // rounds to the nearest unit
        fs::create_directories((out / e.path).parent_path());
        if (!cv::imwrite((out / e.path).string(), units)) throw std::runtime_error((out / e.path).string() + ": cannot be written");
    }
    return depth.size();
}

}  // namespace vobench::synth
