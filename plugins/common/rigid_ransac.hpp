// rigid_ransac.hpp — the rigid motion between two 3-D point sets: RANSAC over 3-point samples with
// Umeyama's closed form (Umeyama 1991, c = 1), the iteration count adapted to the inlier ratio seen
// so far, N = log(1 − p) / log(1 − w³) (Fischler & Bolles 1981; Hartley & Zisserman eq. 4.18), then
// refinement on all inliers with re-classification until the set stops changing — the paper's
// "iterative correction".
#pragma once

#include <Eigen/Geometry>

#include <cstdint>
#include <random>
#include <vector>

namespace vobench::rigid {

struct RansacOptions {
    double inlier_threshold_m = 0.035;
    double probability = 0.99;
    int max_iterations = 1000;
    int refine_iterations = 5;
    // Refinement weights each pair by 1/z² (the depth of its farther point): structured-light and
    // ToF depth noise grows with distance (σ_z ∝ z² for Kinect v1, Khoshelham & Elberink 2012), so
    // near points deserve more trust. Sampling stays unweighted, as in the paper.
    bool depth_weighted_refinement = true;
};

struct RansacResult {
    bool ok = false;
    Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();  // maps `from` onto `to`
    std::vector<int> inliers;
    int iterations = 0;
};

// Finds T with to_i ≈ T · from_i for as many i as possible.
RansacResult ransac_rigid(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to, const RansacOptions& options,
                          std::mt19937_64& rng);

// Least-squares rigid transform (Umeyama) of the indexed pairs; false when degenerate. With weights
// (one per pair, indexed like `from`), the weighted form: centroids and cross-covariance weighted.
bool fit_rigid(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to, const std::vector<int>& index,
               Eigen::Isometry3d& out, const std::vector<double>* weights = nullptr);

}  // namespace vobench::rigid
