#include "synth/depth_geometry.hpp"

#include "metrics/statistics.hpp"
#include "synth/frame_plan.hpp"
#include "synth/renderer.hpp"

#include <Eigen/Eigenvalues>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace vobench::synth {
namespace {

constexpr int kStridePx = 4;              // sampled pixels (consistency) and normal baseline (conditioning)
constexpr double kSmooth = 0.03;          // a bilinear lookup needs its 2×2 depths within 3 % of each other
constexpr std::size_t kMinOverlap = 500;  // points a pair needs to count
constexpr double kIcpRange = 4.0;         // metres: OpenCV's ICP default maximum depth
constexpr double kLeverArm = 2.0;         // metres: rotation rows of J in length units

cv::Mat camera_matrix(const PinholeCamera& c) { return (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1); }

cv::Mat distortion(const PinholeCamera& c) {
    cv::Mat d(1, c.distortion_count, CV_64F);
    for (int k = 0; k < c.distortion_count; ++k) d.at<double>(0, k) = c.distortion[static_cast<std::size_t>(k)];
    return d;
}

double median_of(const std::vector<double>& v) {
    return v.empty() ? std::numeric_limits<double>::quiet_NaN() : metrics::compute_stats(v).median;
}

// Bilinear depth at (u, v) when its four neighbours are measured and lie within kSmooth of each other.
bool smooth_depth(const cv::Mat& depth_m, float u, float v, double& z) {
    const int u0 = static_cast<int>(std::floor(u)), v0 = static_cast<int>(std::floor(v));
    if (u0 < 0 || v0 < 0 || u0 + 1 >= depth_m.cols || v0 + 1 >= depth_m.rows) return false;
    const float z00 = depth_m.at<float>(v0, u0), z01 = depth_m.at<float>(v0, u0 + 1), z10 = depth_m.at<float>(v0 + 1, u0),
                z11 = depth_m.at<float>(v0 + 1, u0 + 1);
    const float lo = std::min({z00, z01, z10, z11}), hi = std::max({z00, z01, z10, z11});
    if (lo <= 0 || hi - lo > kSmooth * lo) return false;
    const double a = u - u0, b = v - v0;
    z = (1 - a) * (1 - b) * z00 + a * (1 - b) * z01 + (1 - a) * b * z10 + a * b * z11;
    return true;
}

}  // namespace

cv::Mat read_depth_metres(const std::filesystem::path& path, double depth_scale) {
    const cv::Mat raw = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
    if (raw.empty() || raw.type() != CV_16UC1) throw std::runtime_error(path.string() + ": not a 16-bit single-channel PNG");
    cv::Mat depth_m;
    raw.convertTo(depth_m, CV_32F, 1.0 / depth_scale);
    return depth_m;
}

void require_camera_size(const std::filesystem::path& depth_path, const cv::Mat& depth, const PinholeCamera& camera) {
    if (depth.cols != camera.width || depth.rows != camera.height)
        throw std::runtime_error(depth_path.string() + ": depth is " + std::to_string(depth.cols) + "×" + std::to_string(depth.rows) +
                                 ", the camera's image " + std::to_string(camera.width) + "×" + std::to_string(camera.height));
}

DepthRays::DepthRays(const PinholeCamera& camera) : camera_(camera) {
    if (camera.width <= 0 || camera.height <= 0 || !(camera.fx > 0) || !(camera.fy > 0))
        throw std::invalid_argument("depth geometry: the camera has no valid size or focal length");
    rays_ = Renderer::make_ray_map(camera).on_plane;
}

namespace {

// Each point of `moved` (frame j's camera frame) against frame j's depth where it lands: its relative
// residual into out.relative[slot[k]].
void compare_depth(const cv::Mat& depth_j, const std::vector<cv::Point3f>& moved, const std::vector<std::size_t>& slot,
                   const DepthRays& rays, PairResiduals& out) {
    const auto pixels = rays.project(moved);
    for (std::size_t k = 0; k < moved.size(); ++k) {
        double measured = 0;
        if (smooth_depth(depth_j, pixels[k].x, pixels[k].y, measured)) out.relative[slot[k]] = (measured - moved[k].z) / moved[k].z;
    }
}

}  // namespace

PairResiduals depth_pair_residuals(const cv::Mat& depth_i, const cv::Mat& depth_j, const Eigen::Isometry3d& j_from_i, const DepthRays& rays,
                                   int stride_px) {
    PairResiduals out;
    std::vector<cv::Point3f> moved;
    std::vector<std::size_t> slot;  // where each moved point's residual goes
    for (int v = 0; v < depth_i.rows; v += stride_px)
        for (int u = 0; u < depth_i.cols; u += stride_px) {
            out.relative.push_back(std::numeric_limits<double>::quiet_NaN());
            const float z = depth_i.at<float>(v, u);
            if (!(z > 0)) continue;
            const Eigen::Vector3d q = j_from_i * rays.point(u, v, z);
            if (q.z() <= 0.05) continue;
            moved.emplace_back(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()));
            slot.push_back(out.relative.size() - 1);
        }
    out.in_front = moved.size();
    compare_depth(depth_j, moved, slot, rays, out);
    return out;
}

PairResiduals depth_pair_residuals_rolling(const cv::Mat& depth_i, const cv::Mat& depth_j,
                                           const std::vector<Eigen::Isometry3d>& world_from_i,
                                           const std::vector<Eigen::Isometry3d>& world_from_j, const DepthRays& rays, int stride_px) {
    PairResiduals out;
    std::vector<Eigen::Vector3d> world;
    std::vector<std::size_t> slot;
    const Eigen::Isometry3d j_middle_from_world = world_from_j[world_from_j.size() / 2].inverse();
    for (int v = 0; v < depth_i.rows; v += stride_px)
        for (int u = 0; u < depth_i.cols; u += stride_px) {
            out.relative.push_back(std::numeric_limits<double>::quiet_NaN());
            const float z = depth_i.at<float>(v, u);
            if (!(z > 0)) continue;
            const Eigen::Vector3d w = world_from_i[static_cast<std::size_t>(v)] * rays.point(u, v, z);
            if ((j_middle_from_world * w).z() <= 0.05) continue;
            world.push_back(w);
            slot.push_back(out.relative.size() - 1);
        }
    const std::vector<cv::Point3f> moved = into_rolling_camera(world, world_from_j, rays);
    out.in_front = moved.size();
    compare_depth(depth_j, moved, slot, rays, out);
    return out;
}

std::vector<cv::Point3f> into_rolling_camera(const std::vector<Eigen::Vector3d>& world,
                                             const std::vector<Eigen::Isometry3d>& world_from_camera, const DepthRays& rays) {
    const auto to_point = [](const Eigen::Vector3d& q) {
        return cv::Point3f(static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(std::max(q.z(), 0.05)));
    };
    const Eigen::Isometry3d middle_from_world = world_from_camera[world_from_camera.size() / 2].inverse();
    std::vector<cv::Point3f> seen;
    seen.reserve(world.size());
    for (const Eigen::Vector3d& w : world) seen.push_back(to_point(middle_from_world * w));
    const auto first = rays.project(seen);
    const int last_row = static_cast<int>(world_from_camera.size()) - 1;
    for (std::size_t k = 0; k < seen.size(); ++k) {
        const auto row = static_cast<std::size_t>(std::clamp(static_cast<int>(std::lround(first[k].y)), 0, last_row));
        seen[k] = to_point(world_from_camera[row].inverse() * world[k]);
    }
    return seen;
}

double median_pair_residual(const PairResiduals& pair) {
    if (pair.in_front < kMinOverlap) return std::numeric_limits<double>::quiet_NaN();
    std::vector<double> residuals;
    for (const double r : pair.relative)
        if (std::abs(r) < kOcclusionResidual) residuals.push_back(std::abs(r));  // NaN compares false: left out
    return residuals.size() < kMinOverlap ? std::numeric_limits<double>::quiet_NaN() : median_of(residuals);
}

double depth_pair_residual(const cv::Mat& depth_i, const cv::Mat& depth_j, const Eigen::Isometry3d& j_from_i, const DepthRays& rays,
                           int stride_px) {
    return median_pair_residual(depth_pair_residuals(depth_i, depth_j, j_from_i, rays, stride_px));
}

std::vector<cv::Point2f> DepthRays::project(const std::vector<cv::Point3f>& points) const {
    std::vector<cv::Point2f> out;
    if (points.empty()) return out;
    const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
    cv::projectPoints(points, zero, zero, camera_matrix(camera_), distortion(camera_), out);
    return out;
}

std::vector<ConsistencyAtGap> reference_consistency(const std::vector<double>& depth_stamps,
                                                    const std::vector<std::filesystem::path>& depth_paths,
                                                    const metrics::Trajectory& reference, const DepthRays& rays,
                                                    const std::vector<int>& gaps, std::size_t max_pairs, double depth_scale) {
    const std::size_t n = std::min(depth_stamps.size(), depth_paths.size());
    std::map<std::size_t, cv::Mat> cache;  // decoded depth images still ahead of the first pair
    const auto depth = [&](std::size_t k) -> const cv::Mat& {
        auto it = cache.find(k);
        if (it == cache.end()) {
            cv::Mat depth_m = read_depth_metres(depth_paths[k], depth_scale);
            require_camera_size(depth_paths[k], depth_m, rays.camera());
            it = cache.emplace(k, std::move(depth_m)).first;
        }
        return it->second;
    };
    std::vector<std::vector<double>> per_gap(gaps.size());
    std::vector<std::array<std::vector<double>, 4>> per_gap_range(gaps.size());
    // Each pair's |residuals| into the depth band of frame i's point (the sampling order of depth_pair_residuals).
    const auto pool_by_range = [&](const cv::Mat& depth_i, const PairResiduals& pr, std::array<std::vector<double>, 4>& bands) {
        std::size_t k = 0;
        for (int v = 0; v < depth_i.rows; v += kStridePx)
            for (int u = 0; u < depth_i.cols; u += kStridePx, ++k) {
                const double r = std::abs(pr.relative[k]);
                if (!(r < kOcclusionResidual)) continue;  // occlusions and NaN left out, as in median_pair_residual
                const double z = depth_i.at<float>(v, u);
                std::size_t band = 0;
                while (band + 1 < bands.size() && z >= kConsistencyRangeEdges[band + 1]) ++band;
                bands[band].push_back(r * 100.0);
            }
    };
    const std::size_t starts = max_pairs > 0 ? std::min(max_pairs, n) : n;
    for (std::size_t s = 0; s < starts; ++s) {
        const std::size_t i = starts == n ? s : s * n / starts;
        cache.erase(cache.begin(), cache.lower_bound(i));
        Eigen::Isometry3d pose_i;
        if (!interpolate_pose(reference, depth_stamps[i], pose_i)) continue;
        for (std::size_t g = 0; g < gaps.size(); ++g) {
            const std::size_t j = i + static_cast<std::size_t>(gaps[g]);
            Eigen::Isometry3d pose_j;
            if (gaps[g] <= 0 || j >= n || !interpolate_pose(reference, depth_stamps[j], pose_j)) continue;
            const PairResiduals pr = depth_pair_residuals(depth(i), depth(j), pose_j.inverse() * pose_i, rays, kStridePx);
            const double r = median_pair_residual(pr);
            if (!std::isfinite(r)) continue;
            per_gap[g].push_back(r * 100.0);
            pool_by_range(depth(i), pr, per_gap_range[g]);
        }
    }
    std::vector<ConsistencyAtGap> out;
    for (std::size_t g = 0; g < gaps.size(); ++g) {
        ConsistencyAtGap c{gaps[g], median_of(per_gap[g]), per_gap[g].size(), {}};
        for (std::size_t b = 0; b < c.by_range_pct.size(); ++b)
            c.by_range_pct[b] =
                per_gap_range[g][b].size() >= kMinOverlap ? median_of(per_gap_range[g][b]) : std::numeric_limits<double>::quiet_NaN();
        out.push_back(c);
    }
    return out;
}

IcpConditioning icp_conditioning(const cv::Mat& depth_m, const DepthRays& rays) {
    const int s = kStridePx;
    Eigen::Matrix<double, 6, 6> info = Eigen::Matrix<double, 6, 6>::Zero();
    std::size_t points = 0;
    const auto valid = [&](int u, int v) {
        const float z = depth_m.at<float>(v, u);
        return z > 0 && z <= kIcpRange;
    };
    for (int v = s; v + s < depth_m.rows; v += s)
        for (int u = s; u + s < depth_m.cols; u += s) {
            if (!valid(u, v) || !valid(u - s, v) || !valid(u + s, v) || !valid(u, v - s) || !valid(u, v + s)) continue;
            const float z = depth_m.at<float>(v, u);
            const float zl = depth_m.at<float>(v, u - s), zr = depth_m.at<float>(v, u + s), zt = depth_m.at<float>(v - s, u),
                        zb = depth_m.at<float>(v + s, u);
            if (std::abs(zr - zl) > kOcclusionResidual * z || std::abs(zb - zt) > kOcclusionResidual * z) continue;  // a depth edge
            const Eigen::Vector3d p = rays.point(u, v, z);
            const Eigen::Vector3d du = rays.point(u + s, v, zr) - rays.point(u - s, v, zl);
            const Eigen::Vector3d dv = rays.point(u, v + s, zb) - rays.point(u, v - s, zt);
            Eigen::Vector3d normal = du.cross(dv);
            if (normal.norm() <= 0) continue;
            normal.normalize();
            Eigen::Matrix<double, 6, 1> J;
            J << p.cross(normal) / kLeverArm, normal;
            info += J * J.transpose();
            ++points;
        }
    IcpConditioning out;
    out.points = points;
    if (points < 6) {
        out.condition = std::numeric_limits<double>::infinity();
        return out;
    }
    info /= static_cast<double>(points);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(info, Eigen::EigenvaluesOnly);
    out.weakest = std::max(eig.eigenvalues()(0), 0.0);
    out.condition = out.weakest > 0 ? eig.eigenvalues()(5) / out.weakest : std::numeric_limits<double>::infinity();
    return out;
}

std::vector<ShadowStep> projector_shadow_steps(const cv::Mat& depth_m, double fx, double baseline_m) {
    constexpr int kMaxHolePx = 30;
    constexpr float kStep = 0.95f;  // the nearer range below 95 % of the farther one
    std::vector<ShadowStep> steps;
    const double fb = fx * baseline_m;
    for (int v = 0; v < depth_m.rows; v += 2) {
        const float* row = depth_m.ptr<float>(v);
        for (int u = 1; u < depth_m.cols; ++u) {
            const float near = row[u - 1];
            if (near <= 0) continue;
            if (row[u] > 0) {
                if (near < kStep * row[u]) steps.push_back({fb * (1.0 / near - 1.0 / row[u]), 0});
                continue;
            }
            const int start = u;
            while (u < depth_m.cols && row[u] <= 0) ++u;
            if (u < depth_m.cols && u - start <= kMaxHolePx && near < kStep * row[u])
                steps.push_back({fb * (1.0 / near - 1.0 / row[u]), u - start});
            --u;  // the pixel after the hole may start the next step
        }
    }
    return steps;
}

}  // namespace vobench::synth
