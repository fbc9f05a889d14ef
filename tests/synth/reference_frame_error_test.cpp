// The turned reference of TUM-format trajectory files (effect reference_frame_error): the camera's
// measured turn, written to groundtruth.txt and synth.json only.
#include "synth/reference_frame_error.hpp"

#include "metrics/trajectory_io.hpp"
#include "synth/camera_catalog.hpp"
#include "synth/sequence_writer.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace vobench;
namespace fs = std::filesystem;

TEST_CASE("reference turn: the rotation of a rotation vector in degrees", "[synth]") {
    CHECK(synth::reference_turn({0, 0, 0}).isApprox(Eigen::Quaterniond::Identity()));
    const Eigen::AngleAxisd about_x(synth::reference_turn({1.05, 0, 0}));
    CHECK(about_x.angle() * 180.0 / M_PI == Approx(1.05).epsilon(1e-12));
    CHECK((about_x.axis() - Eigen::Vector3d::UnitX()).norm() < 1e-12);
    const Eigen::AngleAxisd general(synth::reference_turn({3, -4, 12}));  // |w| = 13°
    CHECK(general.angle() * 180.0 / M_PI == Approx(13.0).epsilon(1e-12));
    CHECK((general.axis() - Eigen::Vector3d(3, -4, 12) / 13.0).norm() < 1e-12);
}

TEST_CASE("synth reference_frame_error: a TUM trajectory's reference is turned by the camera's measured turn; the images are not",
          "[synth]") {
    test::TempDir tmp;
    {
        std::ofstream gt(tmp.path() / "camera.txt");
        gt.precision(17);
        Eigen::Matrix3d level;  // the camera's x (right), y (down), z (forward) in a z-up world
        level << 0, 0, 1, -1, 0, 0, 0, -1, 0;
        for (int k = 0; k <= 20; ++k) {
            const double t = 100.0 + k * 0.01;
            const Eigen::Quaterniond q(Eigen::AngleAxisd(0.5 * (t - 100.0), Eigen::Vector3d::UnitZ()).toRotationMatrix() * level);
            gt << t << " " << 0.01 * k << " 0 1.5 " << q.x() << " " << q.y() << " " << q.z() << " " << q.w() << "\n";
        }
    }
    const auto render = [&](const std::string& camera, const std::string& effects, const std::string& name) {
        synth::SynthOptions o;
        o.sensor = "kinect1";
        o.camera = camera;
        o.trajectory = (tmp.path() / "camera.txt").string();
        o.trajectory_format = "tum";
        o.frames = 2;
        o.seed = 5;
        o.effects = effects;
        o.out = tmp.path() / name;
        REQUIRE(synth::synthesize(o).frames == 2);
        return o.out;
    };
    const std::array<double, 3> measured = synth::camera_by_name_or_file("tum-fr1").reference_turn_deg;
    REQUIRE(Eigen::Vector3d(measured[0], measured[1], measured[2]).norm() > 0.5);  // tum-fr1 has one measured
    const fs::path with = render("tum-fr1", "", "with"), without = render("tum-fr1", "-reference_frame_error", "without");
    const auto gt_with = metrics::read_trajectory(with / "groundtruth.txt").poses;
    const auto gt_without = metrics::read_trajectory(without / "groundtruth.txt").poses;
    REQUIRE(gt_with.size() == gt_without.size());
    REQUIRE_FALSE(gt_with.empty());
    const Eigen::Quaterniond expected = synth::reference_turn(measured);
    for (std::size_t k = 0; k < gt_with.size(); ++k) {
        CHECK(gt_with[k].t == gt_without[k].t);
        CHECK((gt_with[k].p - gt_without[k].p).norm() < 1e-6);                       // turned about the optical centre
        const Eigen::Quaterniond turn = gt_without[k].q.conjugate() * gt_with[k].q;  // in camera coordinates
        CHECK(turn.angularDistance(expected) < 1e-6);
    }
    // The images are the same bytes: only the reference changes.
    CHECK(test::file_bytes(with / "rgb.txt") == test::file_bytes(without / "rgb.txt"));
    std::istringstream lines(test::file_bytes(with / "rgb.txt"));
    std::string line, stamp, file;
    while (std::getline(lines, line))
        if (!line.empty() && line[0] != '#' && std::istringstream(line) >> stamp >> file) {
            CHECK(test::file_bytes(with / file) == test::file_bytes(without / file));
        }
    const auto meta_with = nlohmann::json::parse(test::file_bytes(with / "synth.json"));
    const auto meta_without = nlohmann::json::parse(test::file_bytes(without / "synth.json"));
    CHECK(meta_with["effects"]["reference_frame_error"] == true);  // on by default
    CHECK(meta_with["reference_turn_deg"].get<std::array<double, 3>>() == measured);
    CHECK(meta_without["effects"]["reference_frame_error"] == false);
    CHECK(meta_without["reference_turn_deg"].get<std::array<double, 3>>() == std::array<double, 3>{0, 0, 0});
    // A camera with no measured turn (PUT's own, the sensor's default) writes the poses untouched.
    const fs::path putk2 = render("", "", "putk2");
    const auto gt_putk2 = metrics::read_trajectory(putk2 / "groundtruth.txt").poses;
    REQUIRE(gt_putk2.size() == gt_without.size());
    for (std::size_t k = 0; k < gt_putk2.size(); ++k) CHECK(gt_putk2[k].q.angularDistance(gt_without[k].q) == 0.0);
    CHECK(nlohmann::json::parse(test::file_bytes(putk2 / "synth.json"))["reference_turn_deg"].get<std::array<double, 3>>() ==
          std::array<double, 3>{0, 0, 0});
}
