// gt_fusion.hpp — two independent ground-truth streams fused into one better one (Ceriani et al.
// 2009, §4: Rawseeds fuses its camera-network and laser-based ground truths).
//
// An extended Kalman filter runs forward over the union of both streams' stamps and a
// Rauch–Tung–Striebel smoother runs backward (Rauch, Tung & Striebel 1965; the error-state form on
// SE(3) as in Solà, "Quaternion kinematics for the error-state Kalman filter", 2017, §7–8):
//
//   state      p (world position), R (world←body), v (body velocity), ω (body angular velocity)
//   error      δx = [δp, δθ, δv, δω] ∈ R¹², with R_true = R·Exp(δθ)
//   motion     p ← p + R v Δt,  R ← R·Exp(ω Δt),  v, ω random walks (densities accel_noise², gyro_noise²)
//   measure    a pose (p_m, R_m) from either stream: r = [p_m − p, Log(Rᵀ R_m)], H = [I 0 0 0; 0 I 0 0],
//              noise diag(σ_pos², σ_rot²) of that stream
//   odometry   (optional) relative motion between consecutive stamps, as a measurement of (v, ω)
//
// Each stream is weighted by its own σ; gaps in one stream are bridged by the other and the motion
// model. Output: one pose per distinct stamp, with its 6×6 covariance (position in m², rotation in
// rad² about the body axes).
#pragma once

#include "metrics/pose.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <optional>
#include <vector>

namespace vobench::gt {

struct PoseStream {
    metrics::Trajectory poses;
    double sigma_pos_m = 0.01;
    double sigma_rot_deg = 1.0;
};

struct FusionOptions {
    double accel_noise = 0.5;            // m/s²/√Hz: how fast the body velocity may change
    double gyro_noise = 0.5;             // rad/s²/√Hz
    std::optional<PoseStream> odometry;  // sigma_pos_m in m/s, sigma_rot_deg in °/s (velocity noise)
    double merge_dt = 1e-6;              // stamps closer than this are one step
};

struct FusedPose {
    metrics::StampedPose pose;
    Eigen::Matrix<double, 6, 6> covariance;  // [δp, δθ]
};

// Throws std::invalid_argument on empty input or non-positive sigmas.
std::vector<FusedPose> fuse_ground_truth(const PoseStream& a, const PoseStream& b, const FusionOptions& options);

// TUM trajectory at `file`, and `file`.cov: per line the stamp and the 36 covariance entries, row-major.
void write_fused(const std::filesystem::path& file, const std::vector<FusedPose>& fused);

}  // namespace vobench::gt
