// How much of the depth noise repeats at a pixel from frame to frame: the `synth stats` statistic
// (depth_noise_persistence.hpp) on depth images of known make-up, and Kinect v1's fixed_pattern_noise
// rendered on a wall.
#include "synth/depth_noise_persistence.hpp"
#include "synth/renderer.hpp"
#include "test_support.hpp"
#include "wall_rig.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace vobench;
using namespace vobench::synth;

namespace {

// `frames` depth PNGs (5000 units per metre, 320×240) of a tilted plane about 1.5 m away whose noise
// (σ 6 mm) is √share of a pattern fixed to the pixels plus √(1 − share) drawn anew in every frame.
std::vector<std::filesystem::path> write_noisy_planes(const std::filesystem::path& dir, int frames, double share) {
    std::mt19937 rng(11);
    std::normal_distribution<double> unit(0.0, 1.0);
    cv::Mat fixed(240, 320, CV_64F);
    for (int v = 0; v < fixed.rows; ++v)
        for (int u = 0; u < fixed.cols; ++u) fixed.at<double>(v, u) = unit(rng);
    std::vector<std::filesystem::path> paths;
    for (int f = 0; f < frames; ++f) {
        cv::Mat png(240, 320, CV_16U);
        for (int v = 0; v < png.rows; ++v)
            for (int u = 0; u < png.cols; ++u) {
                const double noise = 0.006 * (std::sqrt(share) * fixed.at<double>(v, u) + std::sqrt(1.0 - share) * unit(rng));
                const double z = 1.5 + 0.0008 * u - 0.0005 * v + noise;
                png.at<uint16_t>(v, u) = static_cast<uint16_t>(std::lround(z * 5000.0));
            }
        paths.push_back(dir / ("depth" + std::to_string(f) + ".png"));
        REQUIRE(cv::imwrite(paths.back().string(), png));
    }
    return paths;
}

// Disparity errors fb/z_measured − fb/z_true over the central 120×120 px of a wall's depth image.
std::vector<double> disparity_errors(const cv::Mat& depth, double z, double fb) {
    std::vector<double> e;
    for (int v = depth.rows / 2 - 60; v < depth.rows / 2 + 60; ++v)
        for (int u = depth.cols / 2 - 60; u < depth.cols / 2 + 60; ++u)
            if (depth.at<float>(v, u) > 0) e.push_back(fb / depth.at<float>(v, u) - fb / z);
    return e;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    REQUIRE(a.size() == b.size());
    double ab = 0, aa = 0, bb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ab += a[i] * b[i];
        aa += a[i] * a[i];
        bb += b[i] * b[i];
    }
    return ab / std::sqrt(aa * bb);
}

}  // namespace

TEST_CASE("synth stats reads the share of the depth noise that stays at its pixel from frame to frame", "[synth][stats]") {
    test::TempDir dir;
    const auto half = write_noisy_planes(dir.path(), 5, 0.5);
    std::filesystem::create_directories(dir.path() / "fresh");
    const auto fresh = write_noisy_planes(dir.path() / "fresh", 5, 0.0);
    const auto repeated = same_pixel_noise_correlation(half, {1, 4}, 0, 5000.0);
    const auto independent = same_pixel_noise_correlation(fresh, {1}, 0, 5000.0);
    REQUIRE(repeated.size() == 2);
    // 4 pairs at gap 1 of 70 patches (10×7 squares of 32 px), 1 pair at gap 4; the 0.2 mm steps of the
    // 16-bit depth add a little noise of their own.
    CHECK(repeated[0].patches == 4 * 70);
    CHECK(repeated[1].patches == 70);
    CHECK(repeated[0].correlation == Approx(0.5).margin(0.05));
    CHECK(repeated[1].correlation == Approx(0.5).margin(0.08));
    CHECK(std::abs(independent[0].correlation) < 0.05);
}

TEST_CASE("synth stats' noise persistence measures only planar patches in range, and names a depth image of another size",
          "[synth][stats]") {
    test::TempDir dir;
    auto paths = write_noisy_planes(dir.path(), 2, 0.5);
    // Too far (4 m): no patch is measured, and the statistic says so rather than reading 0.
    cv::Mat far(240, 320, CV_16U, cv::Scalar(20000));
    REQUIRE(cv::imwrite(paths[1].string(), far));
    const auto none = same_pixel_noise_correlation(paths, {1}, 0, 5000.0);
    CHECK(none[0].patches == 0);
    CHECK(std::isnan(none[0].correlation));
    // A frame of another size.
    REQUIRE(cv::imwrite(paths[1].string(), cv::Mat(120, 160, CV_16U, cv::Scalar(7500))));
    CHECK_THROWS_WITH(same_pixel_noise_correlation(paths, {1}, 0, 5000.0), Catch::Contains(paths[1].string()));
}

TEST_CASE("Kinect v1's fixed_pattern_noise repeats half a pixel's disparity error while it sees the same disparity", "[synth][sensor]") {
    const SensorModel k1 = kinect1();
    REQUIRE(k1.disparity_fixed_share == 0.5);
    REQUIRE(parse_effects("").fixed_pattern_noise);
    const double fb = k1.ir_focal_px * k1.baseline_m;
    // A still camera: frames 0 and 1 draw their own noise; the smooth part and the unit's fixed pattern
    // (which repeats whole, disparity_pattern_test.cpp) are left out to see the per-pixel part alone.
    auto errors = [&](double wall, uint64_t frame, const char* effects) {
        TestRig rig(wall);
        SensorModel sensor = kinect1();
        sensor.effects = parse_effects(effects);
        return disparity_errors(Renderer(rig.scene, sensor, 7).render(frame, rig.pose, rig.pose, 0.1, false).depth_native, wall, fb);
    };
    const char* with = "-correlated_depth_noise,-disparity_pattern";
    const char* without = "-correlated_depth_noise,-fixed_pattern_noise,-disparity_pattern";
    const double repeated = correlation(errors(2.0, 0, with), errors(2.0, 1, with));
    const double anew = correlation(errors(2.0, 0, without), errors(2.0, 1, without));
    // The wall moved from 2 m to 1.2 m: its disparity from 21.8 to 36.3 px, past the 8-px drift.
    const double moved = correlation(errors(2.0, 0, with), errors(1.2, 1, with));
    INFO("same pixel, next frame: " << repeated << " with the effect, " << anew << " without, " << moved << " after the wall moved");
    // The rounding to 1/8 px adds an error of its own (a third of the variance at 2 m), shared only in part.
    CHECK(repeated > 0.25);
    CHECK(repeated < 0.6);
    CHECK(std::abs(anew) < 0.05);
    CHECK(std::abs(moved) < 0.05);
}
