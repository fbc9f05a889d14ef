// The CLI end to end: `vobench track` and `vobench data info` on real TUM frames.
#include "metrics/trajectory_io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>

using namespace vobench;
using Catch::Matchers::Contains;

TEST_CASE("vobench track writes trajectory.txt, timing.csv and a JSON summary", "[cli][track]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_desk");
    test::TempDir out;
    std::string stdout_text;
    const std::string cmd = test::cli().string() + " -q track --dataset tum --path " + dir.string() +
                            " --algorithm c_example --param vx=0.1 --out " + out.path().string() + " --json";
    REQUIRE(test::run_command(cmd, stdout_text) == 0);
    const auto j = nlohmann::json::parse(stdout_text);
    CHECK(j["frames"] == 9);
    CHECK(j["metrics"]["lost_frames"] == 0);
    CHECK(j["metrics"]["ms_per_frame"].get<double>() >= 0.0);
    CHECK(j["metrics"]["ate.rmse"].is_number());
    CHECK(j["metrics"]["rpe.trans.rmse"].is_number());
    CHECK(j["metrics"]["rpe.rot.rmse"].is_number());
    CHECK(j["protocol"]["rpe"]["delta"] == 4.0);

    const auto traj = metrics::read_trajectory(out.path() / "trajectory.txt");
    REQUIRE(traj.poses.size() == 9);
    CHECK(traj.poses[0].t == 1305031453.359684);
    CHECK(traj.poses[8].p.x() == Approx(0.1 * (traj.poses[8].t - traj.poses[0].t)));
    std::ifstream csv(out.path() / "timing.csv");
    std::string header;
    std::getline(csv, header);
    CHECK(header == "index,stamp,process_ms,read_ms,status,stage_integrate_ms,count_elapsed_s,cpu_ms");
}

TEST_CASE("vobench data info describes the fr1/rpy sample", "[cli][data]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    std::string text;
    REQUIRE(test::run_command(test::cli().string() + " -q data info --dataset tum --path " + dir.string() + " --json", text) == 0);
    const auto j = nlohmann::json::parse(text);
    CHECK(j["frames"] == 90);
    CHECK(j["width"] == 640);
    CHECK(j["height"] == 480);
    CHECK(j["gt_poses"] == 307);
    CHECK(j["sensor"] == "kinect1");
}

TEST_CASE("vobench refuses a plugin error cleanly and keeps the frames done", "[cli][track]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_desk");
    test::TempDir out;
    std::string text;
    const std::string cmd = test::cli().string() + " -q track --dataset tum --path " + dir.string() + " --algorithm " +
                            test::fault_plugin("vobench_counter").string() + " --param throw_at=5 --out " + out.path().string() +
                            " --json 2>&1";
    CHECK(test::run_command(cmd, text) == 1);
    CHECK_THAT(text, Contains("plugin 'counter' failed at frame 5 (error): deliberate failure at frame 5"));
    CHECK(metrics::read_trajectory(out.path() / "trajectory.txt").poses.size() == 5);
}

TEST_CASE("vobench eval prints the JSON of the issue's form", "[cli][eval]") {
    VOBENCH_REQUIRE_DATA(dir, "real/trajectories");
    std::string text;
    REQUIRE(test::run_command(test::cli().string() + " eval --gt " + (dir / "freiburg1_xyz-groundtruth.txt").string() + " --est " +
                                  (dir / "freiburg1_xyz-rgbdslam.txt").string() + " --protocol tum-scripts --delta 1 --json 2>/dev/null",
                              text) == 0);
    const auto j = nlohmann::json::parse(text);
    for (const char* key : {"rmse", "mean", "median", "std", "min", "max", "sse", "count"}) {
        CHECK(j["ate"].contains(key));
        CHECK(j["rpe"]["trans"].contains(key));
        CHECK(j["rpe"]["rot_deg"].contains(key));
    }
    CHECK(j["protocol"]["name"] == "tum-scripts");
    CHECK(j["rpe"]["trans"]["rmse"].get<double>() == Approx(0.005763).margin(5e-7));
}
