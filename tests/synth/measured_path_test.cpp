// Effect measured_reference (synth/measured_path.hpp): a smooth camera path sampled at 100 Hz with the
// motion capture's kind of noise added, as TUM's references are; the noise is read back off the samples
// alone and the smoothed path lies closer to the true one than the samples do.
#include "synth/measured_path.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace vobench;
using namespace vobench::synth;

namespace {

constexpr double kDeg = M_PI / 180.0;

// A hand-held-like motion: turning at up to ~60°/s and moving at ~0.3 m/s, smooth at 100 Hz.
Eigen::Isometry3d true_pose(double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(0.35 * std::sin(2.0 * t), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(0.2 * std::sin(1.3 * t + 1.0), Eigen::Vector3d::UnitX()) *
                  Eigen::AngleAxisd(0.1 * std::cos(0.7 * t), Eigen::Vector3d::UnitZ()))
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3d(0.3 * std::sin(t), 0.1 * std::cos(1.5 * t), 0.05 * t);
    return T;
}

// The sampled path with white noise of σ per body axis (rotation) and per world axis (position).
metrics::Trajectory measured(const Eigen::Vector3d& sigma_rot, double sigma_pos, uint64_t seed, std::size_t n = 600) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    metrics::Trajectory poses;
    for (std::size_t i = 0; i < n; ++i) {
        const double t = 100.0 + 0.01 * static_cast<double>(i);
        Eigen::Isometry3d T = true_pose(t);
        const Eigen::Vector3d w(sigma_rot.x() * gauss(rng), sigma_rot.y() * gauss(rng), sigma_rot.z() * gauss(rng));
        if (w.norm() > 0) T.linear() = T.linear() * Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
        T.translation() += sigma_pos * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
        poses.push_back(metrics::StampedPose::from_isometry(t, T));
    }
    return poses;
}

// RMS angle (rad) between each pose and the true one, away from the ends (where a fit is one-sided).
double rotation_error_rms(const metrics::Trajectory& poses) {
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t i = 20; i + 20 < poses.size(); ++i, ++n) {
        const double angle = Eigen::AngleAxisd(true_pose(poses[i].t).linear().transpose() * poses[i].q.toRotationMatrix()).angle();
        sum += angle * angle;
    }
    return std::sqrt(sum / static_cast<double>(n));
}

}  // namespace

TEST_CASE("measured path: the capture's noise is read back off the samples", "[synth][measured_path]") {
    const Eigen::Vector3d sigma(0.06 * kDeg, 0.03 * kDeg, 0.025 * kDeg);  // TUM fr1/rpy's, per body axis
    const PathNoise noise = estimate_path_noise(measured(sigma, 1e-4, 7));
    REQUIRE(noise.differences > 500);
    for (int k = 0; k < 3; ++k) {
        INFO("axis " << k << ": " << noise.rotation_rad[k] / kDeg << "° against " << sigma[k] / kDeg << "°");
        CHECK(noise.rotation_rad[k] == Approx(sigma[k]).epsilon(0.15));
        CHECK(noise.position_m[k] == Approx(1e-4).epsilon(0.15));
    }
}

TEST_CASE("measured path: the smoothed path is closer to the camera's than the measurement", "[synth][measured_path]") {
    const Eigen::Vector3d sigma(0.06 * kDeg, 0.03 * kDeg, 0.025 * kDeg);
    const metrics::Trajectory samples = measured(sigma, 1e-4, 11);
    const MeasuredPath m = smooth_measured_path(samples);
    REQUIRE(m.bandwidth_s > 0);
    CHECK(m.smooth.size() == samples.size());
    CHECK(m.smooth[5].t == samples[5].t);
    const double before = rotation_error_rms(samples), after = rotation_error_rms(m.smooth);
    INFO("bandwidth " << m.bandwidth_s * 1e3 << " ms; rotation error " << before / kDeg << "° -> " << after / kDeg << "°");
    CHECK(after < 0.5 * before);
    // The discrepancy principle: what was taken away is no more than the noise.
    CHECK(m.residual_rotation_rad <= std::sqrt(m.noise.rotation_rad.squaredNorm() / 3.0));
}

TEST_CASE("measured path: an exact path stays as it is within its own precision", "[synth][measured_path]") {
    const MeasuredPath m = smooth_measured_path(measured(Eigen::Vector3d::Zero(), 0.0, 1));
    CHECK(rotation_error_rms(m.smooth) < 0.001 * kDeg);
}

TEST_CASE("measured path: too few or irregular poses are left alone, never made non-finite", "[synth][measured_path]") {
    metrics::Trajectory two = measured(Eigen::Vector3d::Constant(0.05 * kDeg), 1e-4, 3, 2);
    MeasuredPath m = smooth_measured_path(two);
    CHECK(m.bandwidth_s == 0);
    CHECK(m.smooth[1].q.coeffs() == two[1].q.coeffs());
    // Repeated stamps and a gap: no difference across them is used, and every pose stays finite.
    metrics::Trajectory odd = measured(Eigen::Vector3d::Constant(0.05 * kDeg), 1e-4, 4, 60);
    odd[10].t = odd[9].t;
    for (std::size_t i = 30; i < odd.size(); ++i) odd[i].t += 5.0;
    m = smooth_measured_path(odd);
    for (const auto& p : m.smooth) {
        CHECK(p.p.allFinite());
        CHECK(p.q.coeffs().allFinite());
    }
}
