// rgbd::at_middle_row (plugins/common/rgbd_frame.hpp), put_vo's rolling-shutter correction, against
// the rolling shutter as the renderer models it (harness/src/synth/renderer.cpp, row_poses): row v is
// exposed (v / rows − ½)·readout after the middle row while the camera keeps moving. A world point is
// found where such a camera sees it in two consecutive frames; its flow and rolling-shutter position
// must lead back to where a global shutter at the middle row's time would have seen it.
#include "rgbd_frame.hpp"  // plugins/common

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>

namespace {

constexpr double kFocal = 525, kCx = 319.5, kCy = 239.5, kRows = 480, kInterval = 1.0 / 30, kReadout = 0.025;

// The camera (world_from_camera) at time t: turning about its vertical axis and moving sideways.
Eigen::Isometry3d camera_at(double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.6 * t, Eigen::Vector3d::UnitY()).toRotationMatrix();  // 34°/s
    T.translation() = Eigen::Vector3d(0.3 * t, 0.05 * t, 0.1 * t);
    return T;
}

Eigen::Vector2d project(const Eigen::Isometry3d& world_from_camera, const Eigen::Vector3d& world) {
    const Eigen::Vector3d p = world_from_camera.inverse() * world;
    return {kCx + kFocal * p.x() / p.z(), kCy + kFocal * p.y() / p.z()};
}

// Where a rolling-shutter frame whose middle row is exposed at t shows `world`: the row that sees it
// is where the camera was at that row's time (a fixed point, found by iterating).
Eigen::Vector2d seen_rolling(double t, const Eigen::Vector3d& world) {
    Eigen::Vector2d pixel = project(camera_at(t), world);
    for (int i = 0; i < 20; ++i) pixel = project(camera_at(t + (pixel.y() / kRows - 0.5) * kReadout), world);
    return pixel;
}

}  // namespace

TEST_CASE("at_middle_row takes a rolling-shutter feature back to where the middle row's time shows it", "[rgbd]") {
    const double t = 1.0;
    double before_sq = 0, after_sq = 0;
    int n = 0;
    for (double u = -1.5; u <= 1.5; u += 0.5)
        for (double v = -1.0; v <= 1.0; v += 0.25) {
            const Eigen::Vector3d world = camera_at(t) * Eigen::Vector3d(u, v, 2.5);
            const Eigen::Vector2d now = seen_rolling(t, world), before = seen_rolling(t - kInterval, world);
            const Eigen::Vector2d truth = project(camera_at(t), world);
            const cv::Point2f flow(static_cast<float>(now.x() - before.x()), static_cast<float>(now.y() - before.y()));
            const cv::Point2f fixed = vobench::rgbd::at_middle_row(cv::Point2f(static_cast<float>(now.x()), static_cast<float>(now.y())),
                                                                   flow, 480, kReadout, kInterval);
            before_sq += (now - truth).squaredNorm();
            after_sq += std::pow(fixed.x - truth.x(), 2) + std::pow(fixed.y - truth.y(), 2);
            ++n;
        }
    const double before_rms = std::sqrt(before_sq / n), after_rms = std::sqrt(after_sq / n);
    INFO("distance to the middle row's view, RMS: as seen " << before_rms << " px, corrected " << after_rms << " px");
    CHECK(before_rms > 1.0);              // the readout moves features by pixels at this speed
    CHECK(after_rms < 0.1 * before_rms);  // with the wrong sign it would double
}

TEST_CASE("at_middle_row leaves the pixel where there is no readout or no interval", "[rgbd]") {
    const cv::Point2f p(100, 400), flow(12, -3);
    CHECK(vobench::rgbd::at_middle_row(p, flow, 480, 0, kInterval) == p);
    CHECK(vobench::rgbd::at_middle_row(p, flow, 480, kReadout, 0) == p);
    CHECK(vobench::rgbd::at_middle_row(cv::Point2f(100, 240), flow, 480, kReadout, kInterval) == cv::Point2f(100, 240));  // the middle row
}
