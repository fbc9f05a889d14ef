// The fixed disparity pattern of `vobench synth stats --camera` (disparity_pattern.hpp): depth of the test
// box room with a known smooth pattern added to its disparity, while the camera swings, must give that
// pattern back, alike from either half of the frames; exact depth and a low-order field alone must read
// none; a sequence too short to tell reads nothing. And Kinect v1's effect disparity_pattern renders a
// fixed field of that kind.
#include "synth/disparity_pattern.hpp"
#include "synth/box_room.hpp"
#include "synth/renderer.hpp"
#include "synth/smooth_field.hpp"
#include "wall_rig.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <vector>

using namespace vobench;

namespace {

constexpr double kFocalBaseline = 580 * 0.075;

using Offset = std::function<double(int u, int v)>;

// `frames` frames at 30 Hz of the swinging camera (taken at their stamps, exact reference), each
// measured with `offset` added to its disparity.
synth::DepthSequence room_sequence(const synth::DepthRays& rays, const Offset& offset, int frames = 48) {
    synth::DepthSequence s;
    s.reference = test::swinging_reference(0.5, 3.5);
    for (int k = 0; k < frames; ++k) {
        const double stamp = 1.0 + k / 30.0;
        cv::Mat z = test::box_room_view(rays, test::swinging_pose(stamp)).depth;
        for (int v = 0; v < z.rows; ++v)
            for (int u = 0; u < z.cols; ++u) {
                float& depth = z.at<float>(v, u);
                if (depth > 0) depth = static_cast<float>(kFocalBaseline / (kFocalBaseline / depth + offset(u, v)));
            }
        s.stamps.push_back(stamp);
        s.depth_m.push_back(z);
    }
    return s;
}

}  // namespace

TEST_CASE("disparity pattern: a fixed smooth pattern is found again, alike in both halves of the frames", "[synth][stats][distortion]") {
    const synth::DepthRays rays(test::small_distorted_camera());
    // 0.2 px on a lattice of 50 px of this 320-wide image (100 px of a 640-wide one, as Kinect v1 renders).
    const synth::SmoothField field(320, 240, 50.0, 7);
    const Offset pattern = [&](int u, int v) { return 0.2 * field.at(u, v); };
    const synth::DisparityPattern p = synth::estimate_disparity_pattern(room_sequence(rays, pattern), rays, 0.0, kFocalBaseline);
    INFO("rms " << p.rms_px << " px, halves " << p.halves_correlation << ", 64 px " << p.correlation_64px << ", " << p.pairs << " pairs");
    CHECK(p.cell_px == 8);
    CHECK(p.pairs == 44 + 40);
    // The truth at the cells' centres, less its own best a·r² + b·x + c·y + constant over the cells the
    // estimate knows, against the estimate.
    const auto& camera = rays.camera();
    std::vector<Eigen::Vector4d> basis;
    std::vector<double> truth, estimate;
    for (int r = 0; r < p.cells.rows(); ++r)
        for (int c = 0; c < p.cells.cols(); ++c) {
            if (!std::isfinite(p.cells(r, c))) continue;
            const double x = (c * 8 + 4 - camera.cx) / camera.fx, y = (r * 8 + 4 - camera.cy) / camera.fy;
            basis.emplace_back(x * x + y * y, x, y, 1.0);
            truth.push_back(pattern(c * 8 + 4, r * 8 + 4));
            estimate.push_back(p.cells(r, c));
        }
    const auto n = static_cast<Eigen::Index>(truth.size());
    REQUIRE(n > 0.8 * static_cast<double>(p.cells.size()));  // most of the image is seen often enough
    Eigen::MatrixXd a(n, 4);
    for (Eigen::Index k = 0; k < n; ++k) a.row(k) = basis[static_cast<std::size_t>(k)].transpose();
    const Eigen::VectorXd t = Eigen::Map<const Eigen::VectorXd>(truth.data(), n);
    const Eigen::VectorXd e = Eigen::Map<const Eigen::VectorXd>(estimate.data(), n);
    const Eigen::VectorXd rest = t - a * a.colPivHouseholderQr().solve(t);
    const double corr = (rest.array() - rest.mean()).matrix().dot((e.array() - e.mean()).matrix()) /
                        std::sqrt((rest.array() - rest.mean()).square().sum() * (e.array() - e.mean()).square().sum());
    CHECK(corr > 0.9);
    CHECK(std::abs(p.rms_px - std::sqrt(rest.squaredNorm() / static_cast<double>(n))) < 0.01);
    CHECK(p.rms_px > 0.1);
    CHECK(p.rms_px < 0.25);
    CHECK(p.halves_correlation > 0.9);
    CHECK(p.correlation_64px > 0.2);  // blobs of about the lattice's size
}

TEST_CASE("disparity pattern: exact depth and a low-order field alone read none", "[synth][stats][distortion]") {
    const synth::DepthRays rays(test::small_distorted_camera());
    const auto& c = rays.camera();
    const Offset none = [](int, int) { return 0.0; };
    const Offset low_order = [&](int u, int v) {
        const double x = (u - c.cx) / c.fx, y = (v - c.cy) / c.fy;
        return -0.6 * (x * x + y * y) + 0.9 * x - 0.4 * y;
    };
    for (const Offset& offset : {none, low_order}) {
        const synth::DisparityPattern p = synth::estimate_disparity_pattern(room_sequence(rays, offset), rays, 0.0, kFocalBaseline);
        INFO("rms " << p.rms_px << " px");
        CHECK(p.rms_px < 0.02);
    }
}

TEST_CASE("disparity pattern: a sequence too short to tell a fixed pattern from noise reads nothing", "[synth][stats][distortion]") {
    const synth::DepthRays rays(test::small_distorted_camera());
    // 20 frames: each half holds 10 frames, 6 pairs 4 apart and 2 pairs 8 apart.
    const synth::DisparityPattern p = synth::estimate_disparity_pattern(room_sequence(
                                                                            rays, [](int, int) { return 0.0; }, 20),
                                                                        rays, 0.0, kFocalBaseline);
    CHECK(std::isnan(p.rms_px));
    CHECK(std::isnan(p.halves_correlation));
    CHECK(p.cells.size() == 0);
    CHECK(p.pairs == 16 + 12);
}

TEST_CASE("Kinect v1's disparity_pattern: the same field in every frame, another for each seed, no low-order part", "[synth][sensor]") {
    REQUIRE(synth::parse_effects("").disparity_pattern);
    REQUIRE(synth::kinect1().disparity_pattern_sigma_px == 0.15);
    // A still camera before a wall at 2 m, every other effect off: the depth is the pattern alone.
    const double wall = 2.0;
    const auto offsets = [&](uint64_t seed, uint64_t frame, const char* effects) {
        synth::TestRig rig(wall);
        synth::SensorModel sensor = synth::kinect1();
        sensor.effects = synth::parse_effects(effects);
        const double fb = sensor.ir_focal_px * sensor.baseline_m;
        const cv::Mat depth = synth::Renderer(rig.scene, sensor, seed).render(frame, rig.pose, rig.pose, 0.1, false).depth_native;
        cv::Mat out(depth.size(), CV_64F, cv::Scalar(0));
        for (int v = 0; v < depth.rows; ++v)
            for (int u = 0; u < depth.cols; ++u)
                if (depth.at<float>(v, u) > 0) out.at<double>(v, u) = fb / depth.at<float>(v, u) - fb / wall;
        return std::make_pair(out, sensor.depth);
    };
    const auto [first, camera] = offsets(7, 0, "none,+disparity_pattern");
    const cv::Mat later = offsets(7, 5, "none,+disparity_pattern").first, other_unit = offsets(8, 0, "none,+disparity_pattern").first;
    REQUIRE(first.size() == cv::Size(camera.width, camera.height));
    CHECK(cv::norm(first, later, cv::NORM_INF) < 1e-3);  // float depth's rounding only
    CHECK(cv::norm(offsets(7, 0, "none").first, cv::NORM_INF) == 0.0);
    // Its size, and its low-order part: the best a·r² + b·x + c·y + constant over the image.
    Eigen::MatrixXd a(first.rows * first.cols, 4);
    Eigen::VectorXd b(first.rows * first.cols), c(first.rows * first.cols);
    for (int v = 0; v < first.rows; ++v)
        for (int u = 0; u < first.cols; ++u) {
            const double x = (u - camera.cx) / camera.fx, y = (v - camera.cy) / camera.fy;
            const Eigen::Index k = v * first.cols + u;
            a.row(k) << x * x + y * y, x, y, 1.0;
            b(k) = first.at<double>(v, u);
            c(k) = other_unit.at<double>(v, u);
        }
    const Eigen::Vector4d low_order = a.colPivHouseholderQr().solve(b);
    const double rms = std::sqrt(b.squaredNorm() / static_cast<double>(b.size()));
    const double units = (b.array() - b.mean()).matrix().dot((c.array() - c.mean()).matrix()) /
                         std::sqrt((b.array() - b.mean()).square().sum() * (c.array() - c.mean()).square().sum());
    INFO("rms " << rms << " px, low-order part " << low_order.transpose() << ", correlation with another seed's " << units);
    CHECK(rms > 0.05);
    CHECK(rms < 0.25);
    CHECK(low_order.cwiseAbs().maxCoeff() < 0.01);
    CHECK(std::abs(units) < 0.5);
}
