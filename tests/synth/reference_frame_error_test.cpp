// The turned reference of TUM-format trajectory files (effect reference_frame_error).
#include "synth/reference_frame_error.hpp"

#include "metrics/trajectory_io.hpp"
#include "synth/sensor_model.hpp"
#include "synth/sequence_writer.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

using namespace vobench;
namespace fs = std::filesystem;

TEST_CASE("reference frame error: the angle asked for, about an axis uniform on the sphere", "[synth]") {
    CHECK(synth::reference_frame_error(7, 0.0).isApprox(Eigen::Quaterniond::Identity()));
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double z2 = 0;
    const int n = 4000;
    for (int seed = 1; seed <= n; ++seed) {
        const Eigen::AngleAxisd turn(synth::reference_frame_error(static_cast<uint64_t>(seed), 0.02));
        CHECK(turn.angle() == Approx(0.02).epsilon(1e-9));
        sum += turn.axis();
        z2 += turn.axis().z() * turn.axis().z();
    }
    // Uniform on the sphere: the mean axis near 0 (σ per component 1/√(3n) ≈ 0.009), E[z²] = 1/3.
    CHECK((sum / n).norm() < 0.04);
    CHECK(z2 / n == Approx(1.0 / 3).margin(0.02));
    CHECK_FALSE(synth::reference_frame_error(1, 0.02).isApprox(synth::reference_frame_error(2, 0.02)));
}

TEST_CASE("synth +reference_frame_error: a TUM trajectory's reference is the rendered camera turned by 1.5°; the images are not",
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
    const auto render = [&](const std::string& effects, const std::string& name) {
        synth::SynthOptions o;
        o.sensor = "kinect1";
        o.trajectory = (tmp.path() / "camera.txt").string();
        o.trajectory_format = "tum";
        o.frames = 2;
        o.seed = 5;
        o.effects = effects;
        o.out = tmp.path() / name;
        REQUIRE(synth::synthesize(o).frames == 2);
        return o.out;
    };
    const fs::path with = render("+reference_frame_error", "with"), without = render("", "without");
    const auto gt_with = metrics::read_trajectory(with / "groundtruth.txt").poses;
    const auto gt_without = metrics::read_trajectory(without / "groundtruth.txt").poses;
    REQUIRE(gt_with.size() == gt_without.size());
    REQUIRE_FALSE(gt_with.empty());
    const Eigen::Quaterniond expected = synth::reference_frame_error(5, synth::kinect1().reference_frame_error_deg * M_PI / 180.0);
    for (std::size_t k = 0; k < gt_with.size(); ++k) {
        CHECK(gt_with[k].t == gt_without[k].t);
        CHECK((gt_with[k].p - gt_without[k].p).norm() < 1e-6);                       // turned about the optical centre
        const Eigen::Quaterniond turn = gt_without[k].q.conjugate() * gt_with[k].q;  // in camera coordinates
        CHECK(turn.angularDistance(expected) < 1e-6);
        CHECK(Eigen::AngleAxisd(turn).angle() * 180.0 / M_PI == Approx(1.5).epsilon(1e-5));
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
    CHECK(meta_with["effects"]["reference_frame_error"] == true);
    CHECK(meta_with["reference_frame_error"]["angle_deg"].get<double>() == Approx(1.5));
    const Eigen::Vector3d axis(meta_with["reference_frame_error"]["axis"][0].get<double>(),
                               meta_with["reference_frame_error"]["axis"][1].get<double>(),
                               meta_with["reference_frame_error"]["axis"][2].get<double>());
    CHECK((axis - Eigen::AngleAxisd(expected).axis()).norm() < 1e-12);
    CHECK(meta_without["effects"]["reference_frame_error"] == false);  // off by default
    CHECK(meta_without["reference_frame_error"]["angle_deg"].get<double>() == 0.0);
}
