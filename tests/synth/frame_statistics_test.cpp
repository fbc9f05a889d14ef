// `vobench synth stats`: each statistic checked on frames whose true value is known, and on the real
// TUM sample against a direct count.
#include "synth/frame_statistics.hpp"
#include "test_support.hpp"
#include "tum_lists.hpp"  // plugins/common

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include <fstream>
#include <random>
#include <sstream>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

double value(const synth::FolderStatistics& s, const std::string& key) {
    for (const auto& v : s.values)
        if (v.key == key) return v.value;
    FAIL("no statistic " << key);
    return 0;
}

}  // namespace

TEST_CASE("stats: noise, missing depth, plane-fit noise and stamp offsets of frames with known values", "[synth][stats]") {
    test::TempDir tmp;
    fs::create_directories(tmp.path() / "rgb");
    fs::create_directories(tmp.path() / "depth");
    std::mt19937 rng(7);
    std::normal_distribution<double> image_noise(0.0, 3.0), depth_noise(0.0, 0.005);
    std::ofstream rgb(tmp.path() / "rgb.txt"), depth(tmp.path() / "depth.txt");
    for (int k = 0; k < 3; ++k) {
        cv::Mat color(480, 640, CV_8UC3), d(480, 640, CV_16UC1, cv::Scalar(0));
        for (int v = 0; v < 480; ++v)
            for (int u = 0; u < 640; ++u) {
                const double grey = 60 + 0.2 * u + image_noise(rng);  // a smooth ramp: no structure for the estimator
                color.at<cv::Vec3b>(v, u) = cv::Vec3b::all(cv::saturate_cast<uint8_t>(grey));
                if (u >= 16 && v >= 16 && u < 624 && v < 464)
                    d.at<uint16_t>(v, u) = cv::saturate_cast<uint16_t>((2.5 + depth_noise(rng)) * 5000);
            }
        const std::string t = std::to_string(1.0 + k), td = std::to_string(1.010 + k);
        cv::imwrite((tmp.path() / ("rgb/" + t + ".png")).string(), color);
        cv::imwrite((tmp.path() / ("depth/" + td + ".png")).string(), d);
        rgb << t << " rgb/" << t << ".png\n";
        depth << td << " depth/" << td << ".png\n";
    }
    rgb.close();
    depth.close();
    const auto s = synth::measure_folder(tmp.path());
    CHECK(s.frames == 3);
    CHECK(value(s, "image.noise_sigma") == Approx(3.0).epsilon(0.1));
    CHECK(value(s, "missing_depth.border") == Approx(1.0));
    CHECK(value(s, "missing_depth.interior") == Approx(0.0));
    CHECK(value(s, "depth_histogram.2_3m") == Approx(1.0));
    CHECK(value(s, "depth_noise_mm.2_3m") == Approx(5.0).epsilon(0.1));
    // Independent from pixel to pixel: no correlation at any lag (the 0.2-mm rounding to 5000 units a
    // metre is independent too).
    CHECK(std::abs(value(s, "depth_noise_corr.right_1px")) < 0.03);
    CHECK(std::abs(value(s, "depth_noise_corr.right_8px")) < 0.03);
    CHECK(std::abs(value(s, "depth_noise_corr.below_4px")) < 0.03);
    CHECK(value(s, "stamps.offset_mean_ms") == Approx(10.0).epsilon(1e-3));
    CHECK(value(s, "image.fast_corners") < 50);  // a ramp with noise has few corners at threshold 20
    // Noise independent from pixel to pixel, about its 3-px blur: σ²(1 − 1/(2π·9)) + 1/12 for the
    // rounding ≈ 8.8, and barely correlated with the neighbours (measured 0.05: the flat pixels are
    // chosen by a smoothed gradient, which favours noise that happens to be smooth).
    CHECK(value(s, "image.flat_noise_ms") == Approx(8.8).epsilon(0.1));
    CHECK(std::abs(value(s, "image.flat_noise_corr_right")) < 0.06);
    CHECK(std::abs(value(s, "image.flat_noise_corr_below")) < 0.06);
    // White noise spreads its variance (σ² plus 1/12 for the rounding) evenly over the frequency plane;
    // wavelengths of 2–4 px take the annulus 1/4–1/2 cycle a pixel, 3π/16 of it. The ramp lies at long ones.
    CHECK(value(s, "image.spectrum_2_4px") == Approx((9.0 + 1.0 / 12) * 3 * M_PI / 16).epsilon(0.1));
}

TEST_CASE("stats on the real TUM sample: missing depth equals a direct count over its pairs", "[synth][stats][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    const auto s = synth::measure_folder(dir, 10);
    REQUIRE(s.frames == 10);
    // The same ten pairs, counted here without the tool: rgb.txt and depth.txt of this sample are
    // already one-to-one (SOURCES.md), so the k-th lines pair up.
    std::ifstream in(dir / "depth.txt");
    std::stringstream text;
    text << in.rdbuf();
    const auto depth = tum::parse_list(text.str(), "depth.txt");
    double missing = 0, total = 0;
    for (std::size_t k = 0; k < 10; ++k) {
        const cv::Mat d = cv::imread((dir / depth[k * depth.size() / 10].path).string(), cv::IMREAD_UNCHANGED);
        missing += static_cast<double>(d.total()) - cv::countNonZero(d);
        total += static_cast<double>(d.total());
    }
    CHECK(value(s, "missing_depth.all") == Approx(missing / total).epsilon(1e-9));
    // What the tool reports for real Kinect v1 frames: a border that is mostly unmeasured.
    CHECK(value(s, "missing_depth.border") > 2 * value(s, "missing_depth.interior"));
}
