#include "rigid_ransac.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace vobench::rigid {

bool fit_rigid(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to, const std::vector<int>& index,
               Eigen::Isometry3d& out, const std::vector<double>* weights) {
    if (index.size() < 3) return false;
    auto weight = [&](int i) { return weights ? (*weights)[static_cast<std::size_t>(i)] : 1.0; };
    double n = 0;
    Eigen::Vector3d mf = Eigen::Vector3d::Zero(), mt = Eigen::Vector3d::Zero();
    for (int i : index) {
        mf += weight(i) * from[static_cast<std::size_t>(i)];
        mt += weight(i) * to[static_cast<std::size_t>(i)];
        n += weight(i);
    }
    mf /= n;
    mt /= n;
    Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
    for (int i : index) sigma += weight(i) * (to[static_cast<std::size_t>(i)] - mt) * (from[static_cast<std::size_t>(i)] - mf).transpose();
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
    // Degenerate (collinear or coincident points): the second singular value vanishes.
    if (svd.singularValues()(1) < 1e-9 * std::max(1.0, svd.singularValues()(0))) return false;
    Eigen::Vector3d s = Eigen::Vector3d::Ones();
    if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) s(2) = -1;
    out = Eigen::Isometry3d::Identity();
    out.linear() = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
    out.translation() = mt - out.linear() * mf;
    return true;
}

namespace {

std::vector<int> classify(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to, const Eigen::Isometry3d& T,
                          double threshold) {
    std::vector<int> inliers;
    const double t2 = threshold * threshold;
    for (std::size_t i = 0; i < from.size(); ++i)
        if ((T * from[i] - to[i]).squaredNorm() < t2) inliers.push_back(static_cast<int>(i));
    return inliers;
}

}  // namespace

RansacResult ransac_rigid(const std::vector<Eigen::Vector3d>& from, const std::vector<Eigen::Vector3d>& to, const RansacOptions& o,
                          std::mt19937_64& rng) {
    RansacResult best;
    const int n = static_cast<int>(from.size());
    if (n < 3) return best;
    std::uniform_int_distribution<int> pick(0, n - 1);
    int needed = o.max_iterations;
    std::vector<int> sample(3);
    for (int it = 0; it < needed && it < o.max_iterations; ++it) {
        best.iterations = it + 1;
        sample[0] = pick(rng);
        do sample[1] = pick(rng);
        while (sample[1] == sample[0]);
        do sample[2] = pick(rng);
        while (sample[2] == sample[0] || sample[2] == sample[1]);
        Eigen::Isometry3d T;
        if (!fit_rigid(from, to, sample, T)) continue;
        std::vector<int> inliers = classify(from, to, T, o.inlier_threshold_m);
        if (inliers.size() <= best.inliers.size()) continue;
        best.inliers = std::move(inliers);
        best.transform = T;
        best.ok = true;
        const double w = static_cast<double>(best.inliers.size()) / n;
        const double denom = std::log(1.0 - w * w * w);
        needed = denom < 0 ? static_cast<int>(std::ceil(std::log(1.0 - o.probability) / denom)) : o.max_iterations;
    }
    if (!best.ok) return best;
    std::vector<double> weights;
    if (o.depth_weighted_refinement)
        for (std::size_t i = 0; i < from.size(); ++i) {
            const double z = std::max({from[i].z(), to[i].z(), 0.3});
            weights.push_back(1.0 / (z * z));
        }
    // Iterative correction: refit on all inliers, re-classify, until the set is stable.
    for (int r = 0; r < o.refine_iterations; ++r) {
        Eigen::Isometry3d T;
        if (!fit_rigid(from, to, best.inliers, T, o.depth_weighted_refinement ? &weights : nullptr)) break;
        std::vector<int> inliers = classify(from, to, T, o.inlier_threshold_m);
        if (inliers.size() < 3) break;
        const bool same = inliers == best.inliers;
        best.transform = T;
        best.inliers = std::move(inliers);
        if (same) break;
    }
    return best;
}

}  // namespace vobench::rigid
