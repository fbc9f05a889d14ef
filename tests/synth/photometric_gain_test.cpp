// The brightness change between two colour frames (photometric_gain.hpp), checked on frames whose gain
// and motion are known: a textured view moved by a sub-pixel shift and scaled in linear light.
#include "synth/photometric_gain.hpp"
#include "synth/frame_statistics.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <fstream>
#include <limits>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

// A textured scene in linear light (blurred noise at two scales, 0.03–0.5) and the sRGB 8-bit image
// of it shifted by (dx, dy) px and scaled by `gain`.
cv::Mat linear_scene() {
    cv::Mat fine(520, 680, CV_32F), coarse(520, 680, CV_32F);
    cv::RNG rng(11);
    rng.fill(fine, cv::RNG::UNIFORM, 0.0, 1.0);
    rng.fill(coarse, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::GaussianBlur(fine, fine, cv::Size(), 1.5);
    cv::GaussianBlur(coarse, coarse, cv::Size(), 8.0);
    cv::Mat scene = 0.6 * fine + 0.4 * coarse;
    cv::normalize(scene, scene, 0.03, 0.5, cv::NORM_MINMAX);
    return scene;
}

cv::Mat srgb_view(const cv::Mat& scene, double dx, double dy, double gain) {
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, dx - 20, 0, 1, dy - 20);
    cv::Mat view;
    cv::warpAffine(scene, view, shift, cv::Size(640, 480), cv::INTER_CUBIC);
    cv::Mat out(view.size(), CV_8UC1);
    for (int v = 0; v < view.rows; ++v)
        for (int u = 0; u < view.cols; ++u) {
            const double c = std::clamp(gain * view.at<float>(v, u), 0.0, 1.0);
            const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
            out.at<uint8_t>(v, u) = cv::saturate_cast<uint8_t>(255.0 * s);
        }
    return out;
}

}  // namespace

TEST_CASE("gain change: a known gain under a known motion is read back", "[synth][stats]") {
    const cv::Mat scene = linear_scene();
    const cv::Mat a = srgb_view(scene, 0, 0, 1.0);
    for (double gain : {1.0, 1.08, 0.93, 1.25}) {
        const auto g = synth::measure_gain_change(a, srgb_view(scene, 3.4, -2.2, gain));
        REQUIRE(g);
        CHECK(g->corners >= 100);
        CHECK(g->log_ratio == Approx(std::log(gain)).margin(0.006));
    }
}

TEST_CASE("gain change: nothing to track gives no value; images that do not match are refused", "[synth][stats]") {
    const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(128));
    CHECK_FALSE(synth::measure_gain_change(blank, blank));
    const cv::Mat clipped(480, 640, CV_8UC1, cv::Scalar(255));
    const cv::Mat a = srgb_view(linear_scene(), 0, 0, 1.0);
    CHECK_FALSE(synth::measure_gain_change(a, clipped));  // every corner clipped in the second frame
    CHECK_THROWS_AS(synth::measure_gain_change(a, cv::Mat(240, 320, CV_8UC1, cv::Scalar(0))), std::invalid_argument);
}

TEST_CASE("stats: the brightness change between consecutive frames of a folder", "[synth][stats]") {
    test::TempDir tmp;
    fs::create_directories(tmp.path() / "rgb");
    fs::create_directories(tmp.path() / "depth");
    std::ofstream rgb(tmp.path() / "rgb.txt"), depth(tmp.path() / "depth.txt");
    const cv::Mat scene = linear_scene();
    const double gains[] = {1.0, 1.05, 0.945, 0.945};  // changes of ln 1.05 = 4.9 %, ln 0.9 = 10.5 % and 0
    for (int k = 0; k < 4; ++k) {
        const std::string name = std::to_string(k) + ".png";
        cv::Mat color;
        cv::cvtColor(srgb_view(scene, 1.5 * k, 0.7 * k, gains[k]), color, cv::COLOR_GRAY2BGR);
        cv::imwrite((tmp.path() / "rgb" / name).string(), color);
        cv::imwrite((tmp.path() / "depth" / name).string(), cv::Mat(480, 640, CV_16UC1, cv::Scalar(5000)));
        rgb << 10.0 + k / 30.0 << " rgb/" << name << "\n";
        depth << 10.0 + k / 30.0 << " depth/" << name << "\n";
    }
    rgb.close();
    depth.close();
    const auto s = synth::measure_folder(tmp.path());
    auto value = [&](const std::string& key) {
        for (const auto& v : s.values)
            if (v.key == key) return v.value;
        FAIL("no statistic " << key);
        return 0.0;
    };
    CHECK(value("image.gain_change_p90_pct") == Approx(100 * std::log(1.05 / 0.945)).margin(0.6));
    CHECK(value("image.gain_change_median_pct") == Approx(100 * std::log(1.05)).margin(0.6));
    // Frames 0 and 2 only (max_frames 2): frame 2 is compared with frame 1, read from disk, not with
    // frame 0 (that would be 5.6 %).
    const auto every_other = synth::measure_folder(tmp.path(), 2);
    bool found = false;
    for (const auto& v : every_other.values)
        if (v.key == "image.gain_change_median_pct") {
            found = true;
            CHECK(v.value == Approx(100 * std::log(1.05 / 0.945)).margin(0.6));
        }
    CHECK(found);
}

TEST_CASE("exposure fit: the time constant of gains made by the renderer's model is read back", "[synth][stats]") {
    // A scene whose luminance jumps as the view turns, exposed as sequence_writer.cpp does: frame k's
    // gain is target / r_k, r a first-order average of the earlier frames' scene luminance.
    for (double tau : {0.08, 0.32}) {
        std::vector<synth::ExposureFrame> frames;
        std::vector<double> log_scene;
        double reference = 0, previous_gain = 0;
        cv::RNG rng(5);
        double scene = 0.3;
        for (int k = 0; k < 90; ++k) {
            if (k > 0) {
                reference += (1.0 - std::exp(-(1.0 / 30.0) / tau)) * (scene - reference);
                scene *= std::exp(rng.gaussian(0.08));
            } else {
                reference = scene;
            }
            log_scene.push_back(std::log(scene));
            const double gain = 0.34 / reference;
            // Far views the dark ones: the median depth falls as the scene brightens.
            frames.push_back({k / 30.0, scene * gain, k > 0 ? std::log(gain / previous_gain) : 0.0, 3.0 - std::log(scene)});
            previous_gain = gain;
        }
        const auto fit = synth::fit_exposure_time_constant(frames);
        REQUIRE(fit);
        CHECK(fit->time_constant_s == Approx(tau).epsilon(0.01));
        CHECK(fit->rms < 1e-9);
        CHECK(fit->rms_of_gain > 0.05);
        double mean = 0, ss = 0;
        for (double l : log_scene) mean += l / static_cast<double>(log_scene.size());
        for (double l : log_scene) ss += (l - mean) * (l - mean);
        CHECK(fit->scene_log_sd == Approx(std::sqrt(ss / static_cast<double>(log_scene.size()))).epsilon(1e-9));
        CHECK(fit->scene_depth_correlation == Approx(-1.0).margin(1e-9));
        // Without depth on any frame there is no correlation.
        for (auto& f : frames) f.median_depth_m = std::numeric_limits<double>::quiet_NaN();
        CHECK(std::isnan(synth::fit_exposure_time_constant(frames)->scene_depth_correlation));
    }
    CHECK_FALSE(synth::fit_exposure_time_constant(std::vector<synth::ExposureFrame>(9)));
}
