// Table 4 of Kraft et al. (2016) from the real PUTK² marker trajectories.
#include "metrics/trajectory_stats.hpp"
#include "metrics/trajectory_io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

using namespace vobench::metrics;

TEST_CASE("traj stats reproduces Table 4 of Kraft et al. 2016 to 4 decimals", "[metrics][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "putk2-groundtruth");
    struct Row {
        int file;
        std::size_t lines;
        double length, velocity;
    };
    // Sequence k is trajectory(k+1).txt (SOURCES.md).
    const Row table4[] = {{2, 1540, 18.7064, 0.1215}, {3, 2564, 31.6145, 0.1233}, {4, 2755, 39.2709, 0.1426}, {5, 2855, 33.3703, 0.1169},
                          {6, 411, 6.5381, 0.1595},   {7, 170, 6.3842, 0.3778},   {8, 87, 6.4865, 0.7542},    {9, 60, 6.1143, 1.0363}};
    for (const Row& row : table4) {
        ReadOptions o;
        o.format = TrajectoryFormat::Putk2Raw;
        const auto t = read_trajectory(dir / ("trajectory" + std::to_string(row.file) + ".txt"), o);
        const TrajectoryStats s = compute_trajectory_stats(t.poses, 10.0);
        INFO("trajectory" << row.file);
        CHECK(s.poses == row.lines);
        CHECK(s.duration_s == Approx((row.lines - 1) / 10.0));
        CHECK(s.length_m == Approx(row.length).margin(5e-5));
        CHECK(s.mean_velocity_mps == Approx(row.velocity).margin(5e-5));
    }
}

TEST_CASE("camera ground truth is marker pose times camera-in-marker (eq. 10)", "[metrics][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "putk2-groundtruth");
    ReadOptions o;
    o.format = TrajectoryFormat::Putk2Raw;
    const auto marker = read_trajectory(dir / "trajectory2.txt", o);
    o.camera_in_marker = read_camera_in_marker(dir / "cameraZnacznikKin1.txt");
    const auto camera = read_trajectory(dir / "trajectory2.txt", o);
    REQUIRE(marker.poses.size() == camera.poses.size());
    for (std::size_t k = 0; k < marker.poses.size(); k += 97) {
        const Eigen::Isometry3d expected = marker.poses[k].isometry() * *o.camera_in_marker;
        CHECK((camera.poses[k].isometry().matrix() - expected.matrix()).norm() < 1e-9);
    }
    // The Kinect v1 sits ~0.23 m from the marker centre: the camera path differs from the marker path.
    CHECK(o.camera_in_marker->translation().norm() == Approx(0.2347).margin(1e-3));
}
