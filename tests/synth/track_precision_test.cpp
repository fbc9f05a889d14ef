// The tracker-precision statistic of `synth stats` (track_precision.hpp) on frames with known content.
#include "synth/track_precision.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

using namespace vobench::synth;

namespace {

// A blurred random texture, and the same moved by (dx, dy) px, each with its own white noise of σ.
std::pair<cv::Mat, cv::Mat> moved_pair(double dx, double dy, double sigma, unsigned seed) {
    cv::Mat texture(520, 680, CV_32F);
    cv::RNG rng(seed);
    rng.fill(texture, cv::RNG::UNIFORM, 0, 255);
    cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.5);
    cv::normalize(texture, texture, 40, 215, cv::NORM_MINMAX);
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
    cv::Mat moved;
    cv::warpAffine(texture, moved, shift, texture.size(), cv::INTER_CUBIC);
    const cv::Rect inner(20, 20, 640, 480);
    std::pair<cv::Mat, cv::Mat> out;
    for (auto [from, to] : {std::make_pair(&texture, &out.first), std::make_pair(&moved, &out.second)}) {
        cv::Mat noise((*from)(inner).size(), CV_32F);
        rng.fill(noise, cv::RNG::NORMAL, 0, sigma);
        cv::Mat noisy = (*from)(inner) + noise;
        noisy.convertTo(*to, CV_8U);
    }
    return out;
}

}  // namespace

TEST_CASE("track precision: small without noise, growing with it; blank frames give none; sizes must match", "[synth][stats]") {
    const auto clean = moved_pair(2.3, -1.7, 0.0, 3);
    const auto fb_clean = forward_backward_median_px(clean.first, clean.second);
    REQUIRE(fb_clean);
    CHECK(*fb_clean < 0.05);
    double last = *fb_clean;
    for (double sigma : {2.0, 6.0}) {
        const auto noisy = moved_pair(2.3, -1.7, sigma, 3);
        const auto fb = forward_backward_median_px(noisy.first, noisy.second);
        REQUIRE(fb);
        INFO("noise σ " << sigma << ": " << *fb << " px");
        CHECK(*fb > 1.5 * last);
        last = *fb;
    }
    CHECK(last < 1.0);
    const cv::Mat blank(480, 640, CV_8U, cv::Scalar(128));
    CHECK_FALSE(forward_backward_median_px(blank, blank));
    CHECK_THROWS_AS(forward_backward_median_px(blank, blank(cv::Rect(0, 0, 320, 240)).clone()), std::invalid_argument);
    CHECK_THROWS_AS(forward_backward_median_px(cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0)), blank), std::invalid_argument);
}
