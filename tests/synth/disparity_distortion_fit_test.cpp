// `vobench synth fit-distortion` (disparity_distortion_fit.hpp): depth of the test box room distorted by
// a known disparity offset field while the camera swings must give that field back; a folder that
// cannot be read is an error naming the file.
#include "synth/disparity_distortion_fit.hpp"
#include "synth/box_room.hpp"
#include "synth/reference_frame_error.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <fstream>

using namespace vobench;

namespace {

constexpr double kFocalBaseline = 580 * 0.075;

// What a Kinect with the offset field `delta` measures of the true depth `z`: disparity + δ(x, y).
cv::Mat distorted(const cv::Mat& z, const synth::PinholeCamera& c, const synth::DisparityOffset& delta) {
    cv::Mat out(z.size(), CV_32FC1, cv::Scalar(0));
    for (int v = 0; v < z.rows; ++v)
        for (int u = 0; u < z.cols; ++u) {
            const double x = (u - c.cx) / c.fx, y = (v - c.cy) / c.fy, depth = z.at<float>(v, u);
            if (depth > 0)
                out.at<float>(v, u) = static_cast<float>(
                    kFocalBaseline / (kFocalBaseline / depth + delta[0] * (x * x + y * y) + delta[1] * x + delta[2] * y));
        }
    return out;
}

// 48 frames at 30 Hz of the swinging camera, depth distorted by `delta`, each taken `latency_s` before
// its stamp; the reference describes a frame turned by `turn_deg` from the camera's (exact otherwise).
synth::DepthSequence room_sequence(const synth::DepthRays& rays, const synth::DisparityOffset& delta, double latency_s = 0,
                                   const std::array<double, 3>& turn_deg = {0, 0, 0}) {
    synth::DepthSequence s;
    s.reference = test::swinging_reference(0.5, 3.0);
    synth::turn_reference_frame(s.reference, synth::reference_turn(turn_deg));
    for (int k = 0; k < 48; ++k) {
        const double stamp = 1.0 + k / 30.0;
        s.stamps.push_back(stamp);
        s.depth_m.push_back(distorted(test::box_room_view(rays, test::swinging_pose(stamp - latency_s)).depth, rays.camera(), delta));
    }
    return s;
}

}  // namespace

TEST_CASE("disparity offset: undoing it inverts what the sensor added", "[synth][stats][distortion]") {
    const auto camera = test::small_distorted_camera();
    const synth::DepthRays rays(camera);
    const synth::DisparityOffset delta{-0.6, 0.9, -0.4};
    const cv::Mat truth = test::box_room_view(rays, test::swinging_pose(1.0)).depth;
    const cv::Mat back = synth::undo_disparity_offset(distorted(truth, camera, delta), camera, delta, kFocalBaseline);
    double worst = 0;
    for (int v = 0; v < truth.rows; ++v)
        for (int u = 0; u < truth.cols; ++u) worst = std::max(worst, std::abs(double(back.at<float>(v, u)) - truth.at<float>(v, u)));
    CHECK(worst < 1e-5);
    // Missing depth stays missing; no offset leaves the depth as it is.
    cv::Mat holes = truth.clone();
    holes.at<float>(10, 10) = 0;
    CHECK(synth::undo_disparity_offset(holes, camera, delta, kFocalBaseline).at<float>(10, 10) == 0.0f);
    CHECK(cv::norm(synth::undo_disparity_offset(truth, camera, {0, 0, 0}, kFocalBaseline), truth, cv::NORM_INF) < 1e-5);
}

TEST_CASE("fit-distortion: a known disparity offset field is found again, and none where the sensor has none",
          "[synth][stats][distortion]") {
    const synth::DepthRays rays(test::small_distorted_camera());
    synth::DistortionFitOptions options;
    options.depth_latency_s = 0;  // the images are taken at their stamps here
    options.iterations = 6;
    for (const synth::DisparityOffset truth : {synth::DisparityOffset{-0.6, 0.9, -0.4}, synth::DisparityOffset{0, 0, 0}}) {
        const synth::DepthSequence s = room_sequence(rays, truth);
        const synth::DistortionFit fit = synth::fit_disparity_distortion(s, rays, options);
        INFO("truth " << truth[0] << ", " << truth[1] << ", " << truth[2] << " → " << fit.delta[0] << ", " << fit.delta[1] << ", "
                      << fit.delta[2] << " (" << fit.pairs << " pairs, " << fit.residuals << " residuals)");
        for (std::size_t k = 0; k < 3; ++k) CHECK(std::abs(fit.delta[k] - truth[k]) < 0.03);
        CHECK(fit.pairs == 16 + 22);  // every second start: (48 − 16) / 2 and (48 − 4) / 2
        std::size_t pairs = 0;
        const double without = synth::corrected_residual_pct(s, rays, 16, {0, 0, 0}, options, pairs);
        const double with = synth::corrected_residual_pct(s, rays, 16, fit.delta, options, pairs);
        CHECK(pairs == 32);
        CHECK(with < 0.01);  // exact depth and poses: only float rounding remains
        if (truth[1] != 0) CHECK(without > 0.1);
    }
}

TEST_CASE("fit-distortion, joint: the field, the depth latency and the reference's turn are found together", "[synth][stats][distortion]") {
    const synth::DepthRays rays(test::small_distorted_camera());
    const synth::DisparityOffset truth{-0.4, 1.0, -1.0};
    const double latency_s = 0.02;
    const std::array<double, 3> turn_deg{1.0, -0.6, 0.3};
    const synth::DepthSequence s = room_sequence(rays, truth, latency_s, turn_deg);
    synth::DistortionFitOptions options;
    options.depth_latency_s = 0.01;  // a start 10 ms off
    options.iterations = 8;
    options.fit_latency = true;
    options.fit_reference_turn = true;
    const synth::DistortionFit fit = synth::fit_disparity_distortion(s, rays, options);
    const Eigen::Vector3d turn = fit.reference_turn_rad * 180.0 / M_PI;
    INFO("field " << fit.delta[0] << ", " << fit.delta[1] << ", " << fit.delta[2] << "; latency " << fit.depth_latency_s * 1e3
                  << " ms; turn " << turn.transpose() << "°");
    for (std::size_t k = 0; k < 3; ++k) CHECK(std::abs(fit.delta[k] - truth[k]) < 0.03);
    CHECK(std::abs(fit.depth_latency_s - latency_s) < 0.5e-3);
    CHECK((turn - Eigen::Vector3d(turn_deg[0], turn_deg[1], turn_deg[2])).norm() < 0.05);
    // The residual at the fitted values is the exact one's; the field alone, at the wrong latency and
    // unturned, leaves more.
    synth::DistortionFitOptions at_fit = options;
    at_fit.depth_latency_s = fit.depth_latency_s;
    at_fit.reference_turn_rad = fit.reference_turn_rad;
    std::size_t pairs = 0;
    CHECK(synth::corrected_residual_pct(s, rays, 16, fit.delta, at_fit, pairs) < 0.01);
    CHECK(synth::corrected_residual_pct(s, rays, 16, fit.delta, options, pairs) > 0.1);
}

TEST_CASE("fit-distortion: a folder that cannot be read is an error naming the file", "[synth][stats][distortion][corpus]") {
    test::TempDir tmp;
    const auto camera = test::small_distorted_camera();
    const auto folder = tmp.path();
    CHECK_THROWS_WITH(synth::read_depth_sequence(folder, camera, 5000.0), Catch::Contains("depth.txt"));
    std::filesystem::create_directories(folder / "depth");
    std::ofstream(folder / "depth.txt") << "# depth\n1.0 depth/1.png\n1.5\n";
    CHECK_THROWS_WITH(synth::read_depth_sequence(folder, camera, 5000.0), Catch::Contains("depth.txt") && Catch::Contains("3"));
    std::ofstream(folder / "depth.txt") << "# depth\n1.0 depth/1.png\n";
    cv::imwrite((folder / "depth" / "1.png").string(), cv::Mat(100, 100, CV_16UC1, cv::Scalar(7000)));
    CHECK_THROWS_WITH(synth::read_depth_sequence(folder, camera, 5000.0), Catch::Contains("1.png") && Catch::Contains("100×100"));
    cv::imwrite((folder / "depth" / "1.png").string(), cv::Mat(camera.height, camera.width, CV_16UC1, cv::Scalar(7000)));
    CHECK_THROWS_WITH(synth::read_depth_sequence(folder, camera, 5000.0), Catch::Contains("groundtruth.txt"));
    // Read, but no pair to fit: an error, not a field of zeros.
    std::ofstream(folder / "groundtruth.txt") << "1.0 0 0 0 0 0 0 1\n1.1 0 0 0 0 0 0 1\n";
    const synth::DepthSequence one = synth::read_depth_sequence(folder, camera, 5000.0);
    CHECK(one.depth_m.size() == 1);
    CHECK_THROWS_WITH(synth::fit_disparity_distortion(one, synth::DepthRays(camera), {}), Catch::Contains("no pair"));
}

TEST_CASE("undo-distortion: a corrected copy of a folder holds the true depth, the rest unchanged", "[synth][stats][distortion]") {
    test::TempDir tmp;
    const auto camera = test::small_distorted_camera();
    const synth::DepthRays rays(camera);
    const synth::DisparityOffset delta{-0.6, 0.9, -0.4};
    const auto in = tmp.path() / "in", out = tmp.path() / "out";
    std::filesystem::create_directories(in / "depth");
    std::filesystem::create_directories(in / "rgb");
    cv::Mat truth = test::box_room_view(rays, test::swinging_pose(1.0)).depth;
    truth.at<float>(5, 7) = 0;  // a hole stays a hole
    cv::Mat units;
    distorted(truth, camera, delta).convertTo(units, CV_16UC1, 5000.0);
    cv::imwrite((in / "depth" / "1.png").string(), units);
    cv::imwrite((in / "rgb" / "1.png").string(), cv::Mat(camera.height, camera.width, CV_8UC3, cv::Scalar(10, 20, 30)));
    std::ofstream(in / "depth.txt") << "# depth\n1.0 depth/1.png\n";
    std::ofstream(in / "rgb.txt") << "# rgb\n1.0 rgb/1.png\n";
    std::ofstream(in / "groundtruth.txt") << "1.0 0 0 0 0 0 0 1\n";

    CHECK(synth::write_corrected_folder(in, out, camera, delta, kFocalBaseline, 5000.0) == 1);
    const cv::Mat back = synth::read_depth_metres(out / "depth" / "1.png", 5000.0);
    double worst = 0;
    for (int v = 0; v < truth.rows; ++v)
        for (int u = 0; u < truth.cols; ++u) worst = std::max(worst, std::abs(double(back.at<float>(v, u)) - truth.at<float>(v, u)));
    CHECK(worst < 0.6 / 5000.0 + 1e-4);  // the 0.2-mm units of the format, twice rounded, and float arithmetic
    CHECK(back.at<float>(5, 7) == 0.0f);
    CHECK(cv::norm(cv::imread((out / "rgb" / "1.png").string()), cv::imread((in / "rgb" / "1.png").string()), cv::NORM_INF) == 0);
    for (const char* name : {"rgb.txt", "depth.txt", "groundtruth.txt"}) CHECK(std::filesystem::exists(out / name));
    // Never over an existing folder's contents (the real data it came from, say).
    CHECK_THROWS_WITH(synth::write_corrected_folder(in, in, camera, delta, kFocalBaseline, 5000.0), Catch::Contains("not an empty folder"));
    CHECK_THROWS_WITH(synth::write_corrected_folder(in, out, camera, delta, kFocalBaseline, 5000.0),
                      Catch::Contains("not an empty folder"));
}

TEST_CASE("undo-distortion: a list naming a path outside the folder is refused before anything is written",
          "[synth][stats][distortion][corpus]") {
    test::TempDir tmp;
    const auto camera = test::small_distorted_camera();
    const auto in = tmp.path() / "in";
    std::filesystem::create_directories(in);
    for (const std::string bad : {"../elsewhere.png", "/tmp/absolute.png", "depth/../../up.png"}) {
        const auto out = tmp.path() / "out";
        std::ofstream(in / "depth.txt") << "1.0 " << bad << "\n";
        CHECK_THROWS_WITH(synth::write_corrected_folder(in, out, camera, {0, 0.5, 0}, kFocalBaseline, 5000.0),
                          Catch::Contains("depth.txt") && Catch::Contains("entry 1") && Catch::Contains("not a path inside"));
        CHECK_FALSE(std::filesystem::exists(out));
    }
    std::ofstream(in / "depth.txt") << "1.0 depth/1.png\n";
    std::ofstream(in / "rgb.txt") << "1.0 rgb/1.png\n2.0 ../../x.png\n";
    CHECK_THROWS_WITH(synth::write_corrected_folder(in, tmp.path() / "out", camera, {0, 0.5, 0}, kFocalBaseline, 5000.0),
                      Catch::Contains("rgb.txt") && Catch::Contains("entry 2"));
    // A listed depth image that is missing is named.
    std::ofstream(in / "rgb.txt") << "1.0 rgb/1.png\n";
    std::filesystem::create_directories(in / "rgb");
    cv::imwrite((in / "rgb" / "1.png").string(), cv::Mat(camera.height, camera.width, CV_8UC3, cv::Scalar(0)));
    CHECK_THROWS_WITH(synth::write_corrected_folder(in, tmp.path() / "out2", camera, {0, 0.5, 0}, kFocalBaseline, 5000.0),
                      Catch::Contains("1.png") && Catch::Contains("16-bit"));
}
