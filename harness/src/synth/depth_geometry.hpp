// depth_geometry.hpp — the statistics of `vobench synth stats` that need the camera model (issue #15):
// how well a folder's ground truth agrees with its own depth images, and how well its depth
// constrains a geometric alignment. Both are measured the same way on real and rendered folders.
//
// Reference consistency. Frame i's depth, moved by the reference's relative motion T_j⁻¹ T_i (poses
// interpolated at the depth stamps) into frame j = i + gap, should land on frame j's depth. The
// residual |z_j(π(x)) − z(x)| / z(x) of each point (every 4th pixel, bilinear depth on a smooth 2×2
// neighbourhood, residuals over 5 % dropped as occlusions) has a median per pair; the statistic is the
// median over pairs, in per cent. With an exact reference it stays at the depth noise whatever the
// gap; when it grows with the gap, the reference disagrees with the images by more the further the
// camera moved (a hand–eye calibration error of the motion-capture rig, for instance, grows with the
// rotation between the two frames). A rendering has an exact reference, so this is the measurement
// behind any model of a real reference's error.
//
// ICP conditioning (Gelfand et al. 2003, "Geometrically stable sampling for the ICP algorithm"): the
// 6×6 point-to-plane information matrix Σ J Jᵀ over the frame's points, J = [(p × n)/L; n] with
// L = 2 m so that rotation is in metres at a typical range. Its smallest eigenvalue is how strongly the
// worst-constrained motion is pinned down; λmax/λmin how lopsided the constraints are (a single plane:
// unbounded). Normals from central differences 4 px apart; points to 4 m (OpenCV's ICP range).
#pragma once

#include "metrics/pose.hpp"
#include "synth/sensor_model.hpp"

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <array>
#include <filesystem>
#include <vector>

namespace vobench::synth {

// Every pixel's viewing ray at unit depth, (x, y, 1), through the camera's distortion model — the
// renderer's own ray map (Renderer::make_ray_map), so a rendering is measured with the rays it was
// cast along.
class DepthRays {
public:
    explicit DepthRays(const PinholeCamera& camera);
    const PinholeCamera& camera() const { return camera_; }
    // The point at depth z (metres) seen at pixel (u, v).
    Eigen::Vector3d point(int u, int v, double z) const {
        return rays_[static_cast<std::size_t>(v) * static_cast<std::size_t>(camera_.width) + static_cast<std::size_t>(u)] * z;
    }
    // Pixel positions of camera-frame points (through the distortion model).
    std::vector<cv::Point2f> project(const std::vector<cv::Point3f>& points) const;

private:
    PinholeCamera camera_;
    std::vector<Eigen::Vector3d> rays_;  // row-major, z = 1
};

// A 16-bit depth PNG in metres (CV_32F, 0 = missing; `depth_scale` units per metre). Throws
// std::runtime_error naming `path` when it is missing or not a 16-bit single-channel image.
cv::Mat read_depth_metres(const std::filesystem::path& path, double depth_scale);

// Throws std::runtime_error naming `depth_path` when `depth` is not the camera's image size.
void require_camera_size(const std::filesystem::path& depth_path, const cv::Mat& depth, const PinholeCamera& camera);

// Relative depth residuals beyond this are occlusions (another surface), not errors.
constexpr double kOcclusionResidual = 0.05;

// Frame i's depth (every `stride_px`-th pixel, row by row) moved by `j_from_i` onto frame j's: one
// signed relative residual (z_j − z) / z per sampled pixel, bilinear on a smooth 2×2 neighbourhood of
// frame j; NaN where the pixel has no depth, lands behind the camera or off frame j's smooth depth.
// The same pixels in the same order for any motion, so residuals under two motions line up.
struct PairResiduals {
    std::vector<double> relative;
    std::size_t in_front = 0;  // sampled points with depth that land in front of camera j
};
PairResiduals depth_pair_residuals(const cv::Mat& depth_i, const cv::Mat& depth_j, const Eigen::Isometry3d& j_from_i, const DepthRays& rays,
                                   int stride_px);

// World points as a rolling-shutter camera sees them: each in the camera frame of the image row it
// lands on (`world_from_camera` has one pose per row; the row is found from the middle row's pose,
// then the point is placed once more). Points that land behind the camera get z = 0.05 m.
std::vector<cv::Point3f> into_rolling_camera(const std::vector<Eigen::Vector3d>& world,
                                             const std::vector<Eigen::Isometry3d>& world_from_camera, const DepthRays& rays);

// As depth_pair_residuals, for images whose rows were exposed one after another (a rolling shutter):
// row v of frame i seen from `world_from_i[v]`, of frame j from `world_from_j[v]` (one pose per image
// row). Each point goes into the world at its row's pose and into frame j at the pose of the row it
// lands on (found from j's middle row, then once more).
PairResiduals depth_pair_residuals_rolling(const cv::Mat& depth_i, const cv::Mat& depth_j,
                                           const std::vector<Eigen::Isometry3d>& world_from_i,
                                           const std::vector<Eigen::Isometry3d>& world_from_j, const DepthRays& rays, int stride_px);

// The median |relative residual| of a pair's residuals (those over 5 % dropped as occlusions); NaN when
// fewer than 500 points overlap.
double median_pair_residual(const PairResiduals& pair);

// The median |relative residual| of frame i's depth (every `stride_px`-th pixel) moved by `j_from_i`
// onto frame j's (bilinear on a smooth 2×2 neighbourhood, residuals over 5 % dropped as occlusions);
// NaN when the two overlap in fewer than 500 points. Depths in metres, the camera's image size.
double depth_pair_residual(const cv::Mat& depth_i, const cv::Mat& depth_j, const Eigen::Isometry3d& j_from_i, const DepthRays& rays,
                           int stride_px);

// Depth bands of ConsistencyAtGap::by_range_pct: 0–1, 1–2, 2–3 and beyond 3 m.
constexpr double kConsistencyRangeEdges[] = {0.0, 1.0, 2.0, 3.0};

struct ConsistencyAtGap {
    int gap = 0;            // frames between the two depth images of a pair
    double median_pct = 0;  // median over pairs of the pair's median |relative residual|, per cent (NaN: no pair)
    std::size_t pairs = 0;  // pairs that had enough overlap (≥ 500 points)
    // The same residuals pooled over those pairs' points, median |r| per cent by the depth of frame i's
    // point (kConsistencyRangeEdges; NaN: under 500 points in the band). How much the depth of one surface
    // point changes from frame to frame at each range — what feature-based odometry takes at its key points.
    std::array<double, 4> by_range_pct{};
};

// For each gap, pairs (k, k + gap) of `depth_stamps`/`depth_paths` (sorted, consecutive frames of the
// folder) starting at up to `max_pairs` evenly spaced k (0: every k). Pairs whose stamps the reference
// does not cover are left out. Throws std::runtime_error naming a depth image that cannot be decoded.
std::vector<ConsistencyAtGap> reference_consistency(const std::vector<double>& depth_stamps,
                                                    const std::vector<std::filesystem::path>& depth_paths,
                                                    const metrics::Trajectory& reference, const DepthRays& rays,
                                                    const std::vector<int>& gaps, std::size_t max_pairs, double depth_scale);

struct IcpConditioning {
    double weakest = 0;    // smallest eigenvalue of the information matrix per point (m²)
    double condition = 0;  // largest ÷ smallest eigenvalue (infinity when degenerate)
    std::size_t points = 0;
};

// One frame's conditioning; `depth_m` in metres (CV_32F, 0 = missing), the size of the camera's image.
IcpConditioning icp_conditioning(const cv::Mat& depth_m, const DepthRays& rays);

// The projector's shadow as the depth shows it. Along every second row, each step from a nearer to a
// farther surface (left to right, over 5 % of the nearer range) either meets the farther one directly or
// across a hole of up to 30 px; its geometric shadow is f·b·(1/z_near − 1/z_far) pixels (`fx` the depth
// image's focal length, `baseline_m` the projector's distance from the camera whose image the depth is
// in: for depth registered to colour, the colour camera). A Kinect v1 casts its shadow on that side in
// TUM's registered depth (projector at −x).
struct ShadowStep {
    double predicted_px = 0;  // geometric shadow width
    int hole_px = 0;          // width of the hole beside the step (0: none)
};
std::vector<ShadowStep> projector_shadow_steps(const cv::Mat& depth_m, double fx, double baseline_m);

}  // namespace vobench::synth
