#include "synth/measured_path.hpp"
#include "synth/rotation_vector.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace vobench::synth {
namespace {

double median_of(std::vector<double> v) {
    if (v.empty()) return 0;
    const auto mid = v.begin() + static_cast<long>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

double median_interval(const metrics::Trajectory& poses) {
    std::vector<double> dt;
    for (std::size_t i = 1; i < poses.size(); ++i) dt.push_back(poses[i].t - poses[i - 1].t);
    return median_of(dt);
}

double rms_over_axes(const Eigen::Vector3d& sigma) { return std::sqrt(sigma.squaredNorm() / 3.0); }

}  // namespace

PathNoise estimate_path_noise(const metrics::Trajectory& poses) {
    // The median of a χ²₁ variable is 0.4549 σ²: the robust variance of each axis's third differences.
    // White noise of σ on every sample gives them 20 σ² (coefficients 1, −3, 3, −1); smooth motion adds
    // its jerk, which at 100 Hz is hundredths of the noise (second differences would add its
    // acceleration, a tenth and more on TUM's fast sequences).
    constexpr double kChi2Median = 0.4549;
    std::vector<double> rot[3], pos[3];
    for (std::size_t i = 1; i + 2 < poses.size(); ++i) {
        const double a = poses[i].t - poses[i - 1].t, b = poses[i + 1].t - poses[i].t, c = poses[i + 2].t - poses[i + 1].t;
        const double longest = std::max({a, b, c});
        if (!(a > 0) || !(b > 0) || !(c > 0) || longest - std::min({a, b, c}) > 0.1 * longest) continue;
        // Body-frame steps into, out of and after pose i; the second difference of the steps is the
        // third difference of the orientations.
        const Eigen::Vector3d in = log_rotation(poses[i - 1].q.conjugate() * poses[i].q);
        const Eigen::Vector3d out = log_rotation(poses[i].q.conjugate() * poses[i + 1].q);
        const Eigen::Vector3d after = log_rotation(poses[i + 1].q.conjugate() * poses[i + 2].q);
        const Eigen::Vector3d d3r = after - 2.0 * out + in;
        const Eigen::Vector3d d3p = poses[i + 2].p - 3.0 * poses[i + 1].p + 3.0 * poses[i].p - poses[i - 1].p;
        for (int k = 0; k < 3; ++k) {
            rot[k].push_back(d3r[k] * d3r[k]);
            pos[k].push_back(d3p[k] * d3p[k]);
        }
    }
    PathNoise noise;
    noise.differences = rot[0].size();
    if (noise.differences == 0) return noise;
    for (int k = 0; k < 3; ++k) {
        noise.rotation_rad[k] = std::sqrt(median_of(rot[k]) / kChi2Median / 20.0);
        noise.position_m[k] = std::sqrt(median_of(pos[k]) / kChi2Median / 20.0);
    }
    return noise;
}

metrics::Trajectory smooth_path(const metrics::Trajectory& poses, double bandwidth_s) {
    metrics::Trajectory out = poses;
    if (!(bandwidth_s > 0)) return out;
    const double reach = 3.0 * bandwidth_s;
    std::size_t lo = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const double t = poses[i].t;
        while (lo < poses.size() && poses[lo].t < t - reach) ++lo;
        std::size_t hi = lo;
        while (hi < poses.size() && poses[hi].t <= t + reach) ++hi;
        if (hi - lo < 5) continue;
        // Weighted least squares of a quadratic in (t_j − t); its constant term is the fit at t.
        Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
        Eigen::Matrix3d rhs_p = Eigen::Matrix3d::Zero(), rhs_r = Eigen::Matrix3d::Zero();
        const Eigen::Quaterniond centre = poses[i].q.normalized();
        for (std::size_t j = lo; j < hi; ++j) {
            const double s = poses[j].t - t;
            const double w = std::exp(-0.5 * (s / bandwidth_s) * (s / bandwidth_s));
            const Eigen::Vector3d basis(1.0, s, s * s);
            normal += w * basis * basis.transpose();
            rhs_p += w * basis * poses[j].p.transpose();
            rhs_r += w * basis * log_rotation(centre.conjugate() * poses[j].q).transpose();
        }
        const Eigen::LDLT<Eigen::Matrix3d> solver(normal);
        if (solver.info() != Eigen::Success) continue;
        const Eigen::Matrix3d coef_p = solver.solve(rhs_p), coef_r = solver.solve(rhs_r);
        if (!coef_p.allFinite() || !coef_r.allFinite()) continue;
        out[i].p = coef_p.row(0).transpose();
        out[i].q = (centre * exp_rotation(coef_r.row(0).transpose())).normalized();
    }
    return out;
}

MeasuredPath smooth_measured_path(const metrics::Trajectory& poses) {
    MeasuredPath m;
    m.smooth = poses;
    m.noise = estimate_path_noise(poses);
    const double interval = median_interval(poses);
    const double noise_rot = rms_over_axes(m.noise.rotation_rad);
    if (m.noise.differences < 5 || !(interval > 0) || !(noise_rot > 0)) return m;
    // The orientation decides: its jitter moves a camera's image (0.05° is 0.5 px at 580 px focal
    // length) where the position's (0.1 mm, the files' resolution) moves it by hundredths of one.
    for (const double widths : {1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0}) {
        const metrics::Trajectory candidate = smooth_path(poses, widths * interval);
        Eigen::Vector3d sum_r = Eigen::Vector3d::Zero(), sum_p = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < poses.size(); ++i) {
            sum_r += log_rotation(candidate[i].q.conjugate() * poses[i].q).cwiseAbs2();
            sum_p += (poses[i].p - candidate[i].p).cwiseAbs2();
        }
        const double n = static_cast<double>(poses.size());
        const double residual_rot = std::sqrt(sum_r.sum() / (3.0 * n)), residual_pos = std::sqrt(sum_p.sum() / (3.0 * n));
        if (residual_rot > noise_rot) break;
        m.smooth = candidate;
        m.bandwidth_s = widths * interval;
        m.residual_rotation_rad = residual_rot;
        m.residual_position_m = residual_pos;
    }
    return m;
}

}  // namespace vobench::synth
