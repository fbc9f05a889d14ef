#include "synth/sequence_writer.hpp"
#include "metrics/trajectory_io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// groundtruth.txt must equal marker pose · camera-in-marker (Kraft et al. eq. 10) as written beside it.
void check_eq10(const fs::path& dir) {
    metrics::ReadOptions o;
    o.format = metrics::TrajectoryFormat::Putk2Raw;
    o.camera_in_marker = metrics::read_camera_in_marker(dir / "camera_in_marker.txt");
    const auto from_marker = metrics::read_trajectory(dir / "marker_groundtruth.txt", o).poses;
    const auto gt = metrics::read_trajectory(dir / "groundtruth.txt").poses;
    REQUIRE(from_marker.size() == gt.size());
    for (std::size_t k = 0; k < gt.size(); ++k)
        CHECK((from_marker[k].isometry().matrix() - gt[k].isometry().matrix()).cwiseAbs().maxCoeff() < 1e-9);
}

}  // namespace

TEST_CASE("synth: the same seed writes byte-identical files, another seed other noise", "[synth][determinism]") {
    test::TempDir tmp;
    synth::SynthOptions o;
    o.sensor = "kinect1";
    o.trajectory = "speed2";
    o.frames = 3;
    o.out = tmp.path() / "a";
    synth::synthesize(o);
    o.out = tmp.path() / "b";
    synth::synthesize(o);
    o.seed = 2;
    o.out = tmp.path() / "c";
    synth::synthesize(o);
    for (const char* f : {"rgb.txt", "depth.txt", "groundtruth.txt", "rgb/0.200000.png", "depth/0.200000.png", "synth.json"})
        CHECK(slurp(tmp.path() / "a" / f) == slurp(tmp.path() / "b" / f));
    CHECK(slurp(tmp.path() / "a" / "rgb/0.200000.png") != slurp(tmp.path() / "c" / "rgb/0.200000.png"));
    check_eq10(tmp.path() / "a");
}

TEST_CASE("synth renders along the real PUTK² trajectories, ground truth by eq. 10", "[synth][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "putk2-groundtruth");
    test::TempDir tmp;
    for (int k = 2; k <= 9; ++k) {
        synth::SynthOptions o;
        o.sensor = k % 2 ? "kinect1" : "kinect2";
        o.trajectory = (dir / ("trajectory" + std::to_string(k) + ".txt")).string();
        o.camera_in_marker = (dir / (k % 2 ? "cameraZnacznikKin1.txt" : "cameraZnacznikKin2.txt")).string();
        o.frames = 2;
        o.blur = false;
        o.out = tmp.path() / std::to_string(k);
        INFO(o.trajectory);
        REQUIRE(synth::synthesize(o).frames == 2);
        check_eq10(o.out);
        // And against the real files directly.
        metrics::ReadOptions ro;
        ro.format = metrics::TrajectoryFormat::Putk2Raw;
        ro.camera_in_marker = metrics::read_camera_in_marker(o.camera_in_marker);
        const auto real = metrics::read_trajectory(o.trajectory, ro).poses;
        const auto gt = metrics::read_trajectory(o.out / "groundtruth.txt").poses;
        CHECK((real[1].isometry().matrix() - gt[1].isometry().matrix()).cwiseAbs().maxCoeff() < 1e-9);
    }
}

TEST_CASE("synth refuses bad options with a clear message", "[synth]") {
    test::TempDir tmp;
    synth::SynthOptions o;
    o.out = tmp.path();
    o.trajectory = "nowhere.txt";
    CHECK_THROWS_WITH(synth::synthesize(o), Catch::Matchers::Contains("neither a built-in trajectory"));
    o.trajectory = "explore1";
    o.sensor = "kinect3";
    CHECK_THROWS_WITH(synth::synthesize(o), Catch::Matchers::Contains("unknown sensor 'kinect3'"));
}
