// Frame plans (colour and depth each at its own stamp), named cameras and the effect switches.
#include "synth/frame_plan.hpp"
#include "synth/camera_catalog.hpp"
#include "test_support.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <fstream>

using namespace vobench;
using namespace vobench::synth;
namespace fs = std::filesystem;

namespace {

metrics::StampedPose pose_at(double t, double x, double yaw) {
    metrics::StampedPose p;
    p.t = t;
    p.p = Eigen::Vector3d(x, 0, 0);
    p.q = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
    return p;
}

void write(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
}

}  // namespace

TEST_CASE("poses between two stamps: position linear, rotation by slerp, none outside", "[synth][plan]") {
    const metrics::Trajectory path{pose_at(1.0, 0.0, 0.0), pose_at(2.0, 1.0, 0.4)};
    Eigen::Isometry3d T;
    REQUIRE(interpolate_pose(path, 1.25, T));
    CHECK(T.translation().x() == Approx(0.25));
    CHECK(Eigen::AngleAxisd(T.linear()).angle() == Approx(0.1));
    REQUIRE(interpolate_pose(path, 2.0, T));
    CHECK(T.translation().x() == Approx(1.0));
    CHECK_FALSE(interpolate_pose(path, 0.99, T));
    CHECK_FALSE(interpolate_pose(path, 2.01, T));
}

TEST_CASE("synth stamps from a TUM folder: one frame per associated pair, depth at its own stamp, pairs outside the path left out",
          "[synth][plan]") {
    test::TempDir tmp;
    // Colour at 1.0, 1.1, 1.2, 3.0; depth 12 ms later (3.0 lies beyond the trajectory's end).
    write(tmp.path() / "rgb.txt", "# colour\n1.000 rgb/a.png\n1.100 rgb/b.png\n1.200 rgb/c.png\n3.000 rgb/d.png\n");
    write(tmp.path() / "depth.txt", "1.012 depth/a.png\n1.112 depth/b.png\n1.212 depth/c.png\n3.012 depth/d.png\n");
    const metrics::Trajectory path{pose_at(0.9, 0.0, 0.0), pose_at(2.0, 1.1, 0.0)};
    std::size_t skipped = 0;
    const auto plan = plan_from_tum_stamps(path, tmp.path(), skipped);
    REQUIRE(plan.size() == 3);
    CHECK(skipped == 1);
    CHECK(plan[1].color_stamp == Approx(1.1));
    CHECK(plan[1].depth_stamp == Approx(1.112));
    CHECK(plan[1].color_pose.translation().x() == Approx(0.2));
    CHECK(plan[1].depth_pose.translation().x() == Approx(0.212));
    // With stream latencies each image is taken that long before its stamp; the stamps stay as recorded.
    const auto late = plan_from_tum_stamps(path, tmp.path(), skipped, StampLatency{0.008, 0.020});
    REQUIRE(late.size() == 3);
    CHECK(late[1].color_stamp == Approx(1.1));
    CHECK(late[1].depth_stamp == Approx(1.112));
    CHECK(late[1].color_pose.translation().x() == Approx(0.192));
    CHECK(late[1].depth_pose.translation().x() == Approx(0.192));
    CHECK(late[1].next_pose.translation().x() == Approx(0.202));  // the blur looks 10 ms past the exposure
    // No pair within the path: an error naming the list.
    const metrics::Trajectory elsewhere{pose_at(10.0, 0.0, 0.0), pose_at(11.0, 1.0, 0.0)};
    CHECK_THROWS_WITH(plan_from_tum_stamps(elsewhere, tmp.path(), skipped), Catch::Contains("rgb.txt") && Catch::Contains("time span"));
}

TEST_CASE("synth stamps on the camera's clock: each image at its stream's tick (minus latency), the lists' stamps kept", "[synth][plan]") {
    test::TempDir tmp;
    // 30 Hz ticks from 1.0 s; the colour stamps jitter ±2 ms about them, the depth stamps 12 ms later
    // with their own jitter. Both jitters sum to zero and are uncorrelated with the frame number, so
    // the fitted clock is the true one.
    const double color_jitter[] = {0.002, -0.002, 0.0, 0.0, -0.002, 0.002};
    const double depth_jitter[] = {0.001, -0.001, 0.0, 0.0, -0.001, 0.001};
    std::string rgb = "# colour\n", depth = "# depth\n";
    for (int k = 0; k < 6; ++k) {
        rgb += fmt::format("{:.6f} rgb/{}.png\n", 1.0 + k / 30.0 + color_jitter[k], k);
        depth += fmt::format("{:.6f} depth/{}.png\n", 1.012 + k / 30.0 + depth_jitter[k], k);
    }
    write(tmp.path() / "rgb.txt", rgb);
    write(tmp.path() / "depth.txt", depth);
    const metrics::Trajectory path{pose_at(0.9, 0.0, 0.0), pose_at(2.0, 1.1, 0.0)};  // x = t − 0.9
    std::size_t skipped = 0;
    const auto plan = plan_from_tum_stamps(path, tmp.path(), skipped, StampLatency{0.005, 0.018}, true);
    REQUIRE(plan.size() == 6);
    for (int k = 0; k < 6; ++k) {
        INFO("frame " << k);
        CHECK(plan[k].color_stamp == Approx(1.0 + k / 30.0 + color_jitter[k]));  // as recorded
        CHECK(plan[k].color_pose.translation().x() == Approx(1.0 + k / 30.0 - 0.005 - 0.9).margin(2e-6));
        CHECK(plan[k].depth_pose.translation().x() == Approx(1.012 + k / 30.0 - 0.018 - 0.9).margin(2e-6));
    }
    // Off the clock (the default), frame 1 is taken at its stamp, 2 ms early.
    const auto at_stamps = plan_from_tum_stamps(path, tmp.path(), skipped, StampLatency{0.005, 0.018});
    CHECK(at_stamps[1].color_pose.translation().x() == Approx(1.0 + 1 / 30.0 - 0.002 - 0.005 - 0.9).margin(2e-6));
}

TEST_CASE("stamp_offsets moves each depth image by at most 16 ms, reproducibly", "[synth][plan]") {
    metrics::Trajectory path;
    for (int k = 0; k < 20; ++k) path.push_back(pose_at(0.1 * k, 0.1 * k, 0.0));
    auto a = plan_every_pose(path), b = plan_every_pose(path);
    offset_depth_stamps(a, path, 3);
    offset_depth_stamps(b, path, 3);
    int moved = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        CHECK(std::abs(a[k].depth_stamp - a[k].color_stamp) <= 0.016 + 1e-12);
        CHECK(a[k].depth_stamp == b[k].depth_stamp);
        CHECK(a[k].depth_pose.translation().x() == Approx(a[k].depth_stamp).margin(1e-12));
        moved += a[k].depth_stamp != a[k].color_stamp;
    }
    CHECK(moved >= 15);
}

TEST_CASE("a TUM motion-capture path (z up) is turned into the office frame (z down), a PUTK² one left alone", "[synth][plan]") {
    Eigen::Isometry3d tum = Eigen::Isometry3d::Identity();  // camera looking level along +x, image down = world −z
    tum.linear().col(0) = Eigen::Vector3d(0, -1, 0);
    tum.linear().col(1) = Eigen::Vector3d(0, 0, -1);
    tum.linear().col(2) = Eigen::Vector3d(1, 0, 0);
    tum.translation() = Eigen::Vector3d(1, 2, 1.5);
    const Eigen::Isometry3d M = office_from_world({tum}, 3.0);
    const Eigen::Isometry3d office = M * tum;
    CHECK(office.linear()(2, 1) == Approx(1.0));               // image down is the office's +z
    CHECK(office.translation().z() == Approx(1.5));            // 1.5 m above the floor at z = 3
    CHECK((M * Eigen::Vector3d(5, 5, 0)).z() == Approx(3.0));  // TUM's floor at z = 0
    Eigen::Isometry3d putk2 = Eigen::Isometry3d::Identity();
    putk2.linear() = (M * tum).linear();
    CHECK(office_from_world({putk2}, 3.0).isApprox(Eigen::Isometry3d::Identity()));
}

TEST_CASE("cameras by name carry TUM's published calibration and a camera file is checked line by line", "[synth][camera]") {
    const CameraSpec fr1 = camera_by_name_or_file("tum-fr1");
    CHECK(fr1.color.width == 640);
    CHECK(fr1.color.fx == 517.3);
    CHECK(fr1.color.distortion[4] == 1.1633);
    CHECK(fr1.depth_divisor == 1);
    CHECK(camera_by_name_or_file("putk2-kinect1").depth_divisor == 2);
    const SensorModel k1 = with_color_camera(kinect1(), fr1);
    CHECK(k1.depth.width == 640);
    CHECK(k1.depth.fx == 517.3);
    const SensorModel k2 = with_color_camera(kinect2(), fr1);
    CHECK(k2.depth.width == 512);  // Kinect v2 keeps its own depth camera
    CHECK_THROWS_WITH(camera_by_name_or_file("tum-fr9"), Catch::Contains("tum-fr1") && Catch::Contains("tum-fr9"));
    test::TempDir tmp;
    write(tmp.path() / "good.txt", "# w h fx fy cx cy k1 k2\n800 600 500 500 400 300 0.1 -0.2\n");
    const CameraSpec good = camera_by_name_or_file((tmp.path() / "good.txt").string());
    CHECK(good.color.width == 800);
    CHECK(good.color.distortion_count == 2);
    for (const char* bad :
         {"640 480 500 500 320\n", "640 480 0 500 320 240\n", "640.5 480 500 500 320 240\n", "640 480 500 500 320 240 x\n",
          "640 480 500 500 320 240 1 2 3 4 5 6 7 8 9\n", "640 480 nan 500 320 240\n", "# nothing\n"}) {
        write(tmp.path() / "bad.txt", bad);
        INFO(bad);
        CHECK_THROWS_WITH(camera_by_name_or_file((tmp.path() / "bad.txt").string()), Catch::Contains("bad.txt"));
    }
}

TEST_CASE("effects: all, none and ±name from the defaults, an unknown name lists the known ones", "[synth][effects]") {
    const Effects defaults = parse_effects("");
    CHECK(defaults.rolling_shutter);
    CHECK_FALSE(defaults.stamp_offsets);
    CHECK(defaults.stamp_latency);  // only real stamps (--stamps) have a latency to model
    CHECK(defaults.stamp_jitter);   // ... and a clock the stamps jitter about
    CHECK_FALSE(parse_effects("-stamp_latency").stamp_latency);
    CHECK_FALSE(parse_effects("-stamp_jitter").stamp_jitter);
    const Effects some = parse_effects("-motion_blur, +stamp_offsets");
    CHECK_FALSE(some.motion_blur);
    CHECK(some.stamp_offsets);
    CHECK(some.depth_noise);
    const Effects only = parse_effects("none,+depth_noise");
    for (const auto& [name, on] : effect_list(only)) CHECK(on == (name == "depth_noise"));
    CHECK_THROWS_WITH(parse_effects("-blurr"), Catch::Contains("blurr") && Catch::Contains("motion_blur"));
}
