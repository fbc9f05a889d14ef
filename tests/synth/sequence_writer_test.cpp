#include "synth/sequence_writer.hpp"
#include "metrics/trajectory_io.hpp"
#include "synth/camera_catalog.hpp"
#include "synth/office.hpp"
#include "synth/sensor_model.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

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
        CHECK(test::file_bytes(tmp.path() / "a" / f) == test::file_bytes(tmp.path() / "b" / f));
    CHECK(test::file_bytes(tmp.path() / "a" / "rgb/0.200000.png") != test::file_bytes(tmp.path() / "c" / "rgb/0.200000.png"));
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

TEST_CASE("synth --stamps: each image at its stream's latency before its stamp, recorded in synth.json; -stamp_latency at the stamps",
          "[synth][stamps]") {
    test::TempDir tmp;
    // A camera 1.5 m above a z-up motion-capture floor, looking level and turning at 1 rad/s about the
    // vertical (TUM's convention), and two frames whose lists carry equal colour and depth stamps.
    {
        std::ofstream gt(tmp.path() / "camera.txt");
        gt.precision(17);
        Eigen::Matrix3d level;  // columns: the camera's x (right), y (down), z (forward) in the world
        level << 0, 0, 1, -1, 0, 0, 0, -1, 0;
        for (int k = 0; k <= 200; ++k) {
            const double t = 100.0 + k * 0.01;
            const Eigen::Quaterniond q(Eigen::AngleAxisd(t - 100.0, Eigen::Vector3d::UnitZ()).toRotationMatrix() * level);
            gt << t << " 0 0 1.5 " << q.x() << " " << q.y() << " " << q.z() << " " << q.w() << "\n";
        }
    }
    fs::create_directories(tmp.path() / "lists");
    std::ofstream(tmp.path() / "lists" / "rgb.txt") << "100.5 rgb/a.png\n100.6 rgb/b.png\n";
    std::ofstream(tmp.path() / "lists" / "depth.txt") << "100.5 depth/a.png\n100.6 depth/b.png\n";
    const auto render = [&](const std::string& effects, const std::string& name) {
        synth::SynthOptions o;
        o.sensor = "kinect1";
        o.camera = "tum-fr1";
        o.trajectory = (tmp.path() / "camera.txt").string();
        o.trajectory_format = "tum";
        o.stamps = tmp.path() / "lists";
        o.effects = effects;
        o.out = tmp.path() / name;
        REQUIRE(synth::synthesize(o).frames == 2);
        return nlohmann::json::parse(test::file_bytes(o.out / "synth.json"));
    };
    const auto with = render("", "with"), without = render("-stamp_latency", "without");
    CHECK(with["effects"]["stamp_latency"] == true);
    CHECK(with["stamp_latency_s"]["color"].get<double>() == Approx(synth::kinect1().color_latency_s));
    CHECK(with["stamp_latency_s"]["depth"].get<double>() == Approx(synth::kinect1().depth_latency_s));
    CHECK(without["stamp_latency_s"]["depth"].get<double>() == 0.0);
    // The disparity distortion as rendered: the camera's, recorded for whoever re-reads the folder.
    const auto field = synth::camera_by_name_or_file("tum-fr1").disparity_distortion_px;
    REQUIRE(with["disparity_distortion_px"].size() == 3);
    for (std::size_t k = 0; k < 3; ++k) CHECK(with["disparity_distortion_px"][k].get<double>() == field[k]);
    // The office and the projector shadow as rendered: TUM's hall for its camera, the fill Kinect v1 has.
    CHECK(with["min_room_m"].get<double>() == synth::camera_by_name_or_file("tum-fr1").min_room_m);
    CHECK(with["min_room_m"].get<double>() > synth::OfficeOptions{}.min_room);
    CHECK(with["shadow_fill_px"].get<int>() == synth::kinect1().shadow_fill_px);
    // Two stamps cannot fit a clock: they are taken as they are, and synth.json says so.
    CHECK(with["effects"]["stamp_jitter"] == true);
    CHECK(with["camera_clock"]["color"]["fitted"] == false);
    // The lists keep the recorded stamps; the images differ (19 ms at 1 rad/s: 1.1°, ≈ 10 px).
    CHECK(test::file_bytes(tmp.path() / "with" / "depth.txt") == test::file_bytes(tmp.path() / "without" / "depth.txt"));
    CHECK(test::file_bytes(tmp.path() / "with" / "depth" / "100.500000.png") !=
          test::file_bytes(tmp.path() / "without" / "depth" / "100.500000.png"));
}
