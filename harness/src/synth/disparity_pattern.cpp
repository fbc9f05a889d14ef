#include "synth/disparity_pattern.hpp"

#include "synth/frame_plan.hpp"

#include <tbb/parallel_for.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vobench::synth {
namespace {

constexpr int kGaps[] = {4, 8};
constexpr int kStridePx = 2;
constexpr double kCellPx640 = 16;    // cell size in pixels of a 640-wide image
constexpr double kMismatchPx = 1.0;  // a disparity residual beyond this is a mismatch, not the pattern
constexpr double kSmoothness = 1.0;  // weight of (δ_k − δ_l)² between neighbouring cells
constexpr double kMinSamples = 50;   // a cell seen fewer times stays unknown
constexpr std::size_t kMinPairsPerHalf = 10;
constexpr std::size_t kChunkPairs = 16;  // pairs whose samples are held at once
constexpr int kLagCells = 4;             // 64 px of a 640-wide image

struct Pair {
    std::size_t i, j;
};

struct Lattice {
    int cell = 16, columns = 0, rows = 0;
    int index(int u, int v) const { return (v / cell) * columns + u / cell; }
    int size() const { return columns * rows; }
};

// One difference δ(q) − δ(p) = r: the cells of the two pixels and the residual.
struct Sample {
    int q, p;
    float r;
};

// The normal equations of all the differences: Σ aaᵀ and Σ a·r for a = e_q − e_p.
struct Normal {
    Eigen::MatrixXd ata;
    Eigen::VectorXd atr;
    explicit Normal(int n) : ata(Eigen::MatrixXd::Zero(n, n)), atr(Eigen::VectorXd::Zero(n)) {}
    void add(const Sample& s) {
        ata(s.q, s.q) += 1;
        ata(s.p, s.p) += 1;
        ata(s.q, s.p) -= 1;
        ata(s.p, s.q) -= 1;
        atr(s.q) += s.r;
        atr(s.p) -= s.r;
    }
};

std::vector<Sample> pair_samples(const cv::Mat& depth_i, const cv::Mat& depth_j, const Eigen::Isometry3d& j_from_i, const DepthRays& rays,
                                 const Lattice& lattice, double focal_baseline) {
    std::vector<cv::Point3f> moved;
    std::vector<int> from;
    for (int v = 0; v < depth_i.rows; v += kStridePx)
        for (int u = 0; u < depth_i.cols; u += kStridePx) {
            const float z = depth_i.at<float>(v, u);
            if (!(z > 0)) continue;
            const Eigen::Vector3d y = j_from_i * rays.point(u, v, z);
            if (y.z() < 0.1) continue;
            moved.emplace_back(static_cast<float>(y.x()), static_cast<float>(y.y()), static_cast<float>(y.z()));
            from.push_back(lattice.index(u, v));
        }
    const std::vector<cv::Point2f> at = rays.project(moved);
    std::vector<Sample> out;
    for (std::size_t k = 0; k < at.size(); ++k) {
        const int u = static_cast<int>(std::lround(at[k].x)), v = static_cast<int>(std::lround(at[k].y));
        if (u < 0 || v < 0 || u >= depth_j.cols || v >= depth_j.rows) continue;
        const double z_j = depth_j.at<float>(v, u), z = moved[k].z;
        if (!(z_j > 0) || std::abs(z_j - z) > kOcclusionResidual * z) continue;
        const double r = focal_baseline * (1.0 / z_j - 1.0 / z);
        const int q = lattice.index(u, v);
        if (std::abs(r) > kMismatchPx || q == from[k]) continue;
        out.push_back({q, from[k], static_cast<float>(r)});
    }
    return out;
}

// δ per cell: the normal equations with the smoothness term and the mean held at 0; NaN where seen too little.
Eigen::MatrixXd solve_cells(const Normal& n, const Lattice& lattice) {
    Eigen::MatrixXd a = n.ata;
    for (int r = 0; r < lattice.rows; ++r)
        for (int c = 0; c < lattice.columns; ++c) {
            const int k = r * lattice.columns + c;
            for (const int l : {c + 1 < lattice.columns ? k + 1 : -1, r + 1 < lattice.rows ? k + lattice.columns : -1}) {
                if (l < 0) continue;
                a(k, k) += kSmoothness;
                a(l, l) += kSmoothness;
                a(k, l) -= kSmoothness;
                a(l, k) -= kSmoothness;
            }
        }
    a.array() += 1.0;  // (Σ δ)²: the differences leave the mean free
    const Eigen::VectorXd delta = a.ldlt().solve(n.atr);
    Eigen::MatrixXd cells(lattice.rows, lattice.columns);
    for (int r = 0; r < lattice.rows; ++r)
        for (int c = 0; c < lattice.columns; ++c) {
            const int k = r * lattice.columns + c;
            cells(r, c) = n.ata(k, k) >= kMinSamples ? delta(k) : DisparityPattern::kUnknown;
        }
    return cells;
}

// Takes the best a·r² + b·x + c·y + constant (x, y the cell centres' normalised coordinates) off the known cells.
void take_off_low_order(Eigen::MatrixXd& cells, const Lattice& lattice, const PinholeCamera& camera) {
    std::vector<Eigen::Vector4d> rows;
    std::vector<double> values;
    const auto basis = [&](int r, int c) { return disparity_field_terms(camera, (c + 0.5) * lattice.cell, (r + 0.5) * lattice.cell); };
    for (int r = 0; r < cells.rows(); ++r)
        for (int c = 0; c < cells.cols(); ++c)
            if (std::isfinite(cells(r, c))) {
                rows.push_back(basis(r, c));
                values.push_back(cells(r, c));
            }
    if (rows.size() < 8) return;
    Eigen::MatrixXd a(static_cast<Eigen::Index>(rows.size()), 4);
    Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t k = 0; k < rows.size(); ++k) {
        a.row(static_cast<Eigen::Index>(k)) = rows[k].transpose();
        b(static_cast<Eigen::Index>(k)) = values[k];
    }
    const Eigen::Vector4d coef = a.colPivHouseholderQr().solve(b);
    for (int r = 0; r < cells.rows(); ++r)
        for (int c = 0; c < cells.cols(); ++c)
            if (std::isfinite(cells(r, c))) cells(r, c) -= basis(r, c).dot(coef);
}

// Pearson correlation of a(r, c) with b(r + dy, c + dx) over the cells known in both.
double correlation(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, int dx, int dy) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
    for (int r = 0; r + dy < a.rows(); ++r)
        for (int c = 0; c + dx < a.cols(); ++c) {
            const double x = a(r, c), y = b(r + dy, c + dx);
            if (!std::isfinite(x) || !std::isfinite(y)) continue;
            sa += x, sb += y, saa += x * x, sbb += y * y, sab += x * y, n += 1;
        }
    if (n < 10) return DisparityPattern::kUnknown;
    const double cov = sab - sa * sb / n, va = saa - sa * sa / n, vb = sbb - sb * sb / n;
    return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : DisparityPattern::kUnknown;
}

}  // namespace

DisparityPattern estimate_disparity_pattern(const DepthSequence& s, const DepthRays& rays, double depth_latency_s,
                                            double focal_baseline_px_m) {
    DisparityPattern out;
    const PinholeCamera& camera = rays.camera();
    Lattice lattice;
    lattice.cell = std::max(2, static_cast<int>(std::lround(kCellPx640 * camera.width / 640.0)));
    lattice.columns = (camera.width + lattice.cell - 1) / lattice.cell;
    lattice.rows = (camera.height + lattice.cell - 1) / lattice.cell;
    out.cell_px = lattice.cell;
    // The pairs the reference covers, with each one's motion (poses at the ticks less the latency).
    std::vector<Pair> pairs;
    std::vector<Eigen::Isometry3d> motion;
    const std::size_t n = std::min(s.stamps.size(), s.depth_m.size());
    for (const int gap : kGaps)
        for (std::size_t i = 0; i + static_cast<std::size_t>(gap) < n; ++i) {
            const std::size_t j = i + static_cast<std::size_t>(gap);
            Eigen::Isometry3d pose_i, pose_j;
            if (!interpolate_pose(s.reference, s.stamps[i] - depth_latency_s, pose_i) ||
                !interpolate_pose(s.reference, s.stamps[j] - depth_latency_s, pose_j))
                continue;
            pairs.push_back({i, j});
            motion.push_back(pose_j.inverse() * pose_i);
        }
    out.pairs = pairs.size();
    const auto first_half = [&](const Pair& p) { return p.j < n / 2; };
    const auto second_half = [&](const Pair& p) { return p.i >= n / 2; };
    if (static_cast<std::size_t>(std::count_if(pairs.begin(), pairs.end(), first_half)) < kMinPairsPerHalf ||
        static_cast<std::size_t>(std::count_if(pairs.begin(), pairs.end(), second_half)) < kMinPairsPerHalf)
        return out;
    Normal all(lattice.size()), first(lattice.size()), second(lattice.size());
    for (std::size_t start = 0; start < pairs.size(); start += kChunkPairs) {
        const std::size_t end = std::min(pairs.size(), start + kChunkPairs);
        std::vector<std::vector<Sample>> samples(end - start);
        tbb::parallel_for(start, end, [&](std::size_t k) {
            samples[k - start] = pair_samples(s.depth_m[pairs[k].i], s.depth_m[pairs[k].j], motion[k], rays, lattice, focal_baseline_px_m);
        });
        for (std::size_t k = start; k < end; ++k)
            for (const Sample& sample : samples[k - start]) {
                all.add(sample);
                if (first_half(pairs[k])) first.add(sample);
                if (second_half(pairs[k])) second.add(sample);
            }
    }
    out.cells = solve_cells(all, lattice);
    Eigen::MatrixXd a = solve_cells(first, lattice), b = solve_cells(second, lattice);
    for (Eigen::MatrixXd* m : {&out.cells, &a, &b}) take_off_low_order(*m, lattice, camera);
    double sum = 0, count = 0;
    for (Eigen::Index k = 0; k < out.cells.size(); ++k)
        if (std::isfinite(out.cells.data()[k])) sum += out.cells.data()[k] * out.cells.data()[k], count += 1;
    if (count > 0) out.rms_px = std::sqrt(sum / count);
    out.halves_correlation = correlation(a, b, 0, 0);
    out.correlation_64px = 0.5 * (correlation(out.cells, out.cells, kLagCells, 0) + correlation(out.cells, out.cells, 0, kLagCells));
    return out;
}

}  // namespace vobench::synth
