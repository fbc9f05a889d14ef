// rigid_refine.hpp — the rigid motion between two sets of RGB-D points, refined under the sensor's
// noise model: each point is uncertain mostly along its viewing ray (depth from disparity or time of
// flight) and little across it (where the pixel is), so a pair's residual r = T·p − q has covariance
//   Σ = R C(p) Rᵀ + C(q),   C(x) = σ_lat(x)² (I − u uᵀ) + σ_ax(x)² u uᵀ,   u = x / |x|,
// with σ_ax = k z² (Kinect v1: k = 1.425e-3 m⁻¹, Khoshelham & Elberink 2012; the disparity model
// z² σ_d / (f b) gives 1.16e-3) and σ_lat = z σ_px / f. A Kinect v1 also adds a fixed offset δ(x, y)
// to every disparity (its calibration error, Herrera et al. 2012; Smisek et al. 2011), so one point
// seen at two image positions n_p, n_q (pinhole-normalised) gets two depths that differ by
// z² (δ(n_q) − δ(n_p)) / (f b) ≈ z² g |n_q − n_p| / (f b), g the field's gradient: Σ gains that along
// q's ray. Not noise but a bias that grows with the image motion, which the residual cannot tell from
// noise of that size. Gauss–Newton on SE(3) minimises Σ ρ(rᵀ Σ⁻¹ r) with Cauchy's ρ (a
// robust M-estimator, Zhang 1997), starting from the RANSAC answer. Umeyama's closed form weighs a
// 3 cm error along the ray of a far point like one across the ray of a near point; this does not.
#pragma once

#include <Eigen/Geometry>

#include <vector>

namespace vobench::rigid {

struct PointNoise {
    double axial_per_z2 = 1.425e-3;    // σ_ax / z², 1/m (Khoshelham & Elberink 2012)
    double lateral_px = 0.25;          // σ of a point's pixel position, px (the tracker's precision)
    double focal_px = 525.0;           // to turn pixels into metres at depth z
    double field_gradient_px = 0;      // g: change of the disparity offset per pinhole-normalised unit, px (0: none)
    double focal_baseline_pxm = 43.5;  // the depth camera's f·b, px·m (Kinect v1: 580 px × 7.5 cm)
    double cauchy_scale = 2.5;         // c of ρ(d²) = c² log(1 + d²/c²), in σ
};

// Refines T (to ≈ T · from) on the indexed pairs; returns false (T untouched) when the system is
// degenerate. Deterministic: the same pairs give the same answer.
bool refine_rigid(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to, const std::vector<int>& index,
                  const PointNoise& noise, Eigen::Isometry3d& T, int iterations = 10);

// The pairs whose residual under T lies within the χ² gate of its own covariance; 7.81 is the 95 %
// point of χ² with 3 degrees of freedom (Hartley & Zisserman 2004, Table 4.2).
std::vector<int> consistent_pairs(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to, const PointNoise& noise,
                                  const Eigen::Isometry3d& T, double chi2 = 7.81);

struct GatedRefinement {
    bool ok = false;
    Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
    std::vector<int> inliers;
};

// RANSAC's inliers share one fixed distance threshold, too loose for a near point and too tight for a
// far one; so: refine on them, take as inliers the pairs within the gate under the refined motion,
// refine again, until the set stops changing (at most `rounds` times). The set that results depends
// on the geometry more than on which sample won RANSAC.
GatedRefinement refine_gated(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to,
                             const std::vector<int>& inliers, const PointNoise& noise, const Eigen::Isometry3d& start, double chi2 = 7.81,
                             int rounds = 3, std::size_t min_inliers = 10);

}  // namespace vobench::rigid
