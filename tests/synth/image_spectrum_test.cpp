// The spectrum statistic of `synth stats` (image_spectrum.hpp) on images whose spectrum is known.
#include "synth/image_spectrum.hpp"

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include <cmath>

using namespace vobench::synth;

namespace {

constexpr int kWidth = 672, kHeight = 512;  // 640×480 inside the 16-px border

cv::Mat white_noise(double sigma, unsigned seed) {
    cv::Mat noise(kHeight, kWidth, CV_32F);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::NORMAL, 0, sigma);
    return noise;
}

// White noise shaped by the filter 1/f^(α/2) in the frequency domain: power ∝ 1/f^α, the DC removed.
cv::Mat power_law_field(double alpha, unsigned seed) {
    cv::Mat spectrum;
    cv::dft(white_noise(1.0, seed), spectrum, cv::DFT_COMPLEX_OUTPUT);
    for (int i = 0; i < spectrum.rows; ++i)
        for (int j = 0; j < spectrum.cols; ++j) {
            const double fy = static_cast<double>(i <= kHeight / 2 ? i : i - kHeight) / kHeight;
            const double fx = static_cast<double>(j <= kWidth / 2 ? j : j - kWidth) / kWidth;
            const double f = std::hypot(fx, fy);
            spectrum.at<cv::Vec2f>(i, j) *= f > 0 ? static_cast<float>(std::pow(f, -alpha / 2)) : 0.0f;
        }
    cv::Mat field;
    cv::dft(spectrum, field, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
    return field;
}

}  // namespace

TEST_CASE("image spectrum: a sinusoid's variance lands in its octave", "[synth][stats]") {
    cv::Mat wave(kHeight, kWidth, CV_32F);
    const double amplitude = 40, wavelength = 11.3;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            wave.at<float>(y, x) = static_cast<float>(128 + amplitude * std::sin(2 * M_PI * (x + 0.3 * y) / wavelength));
    // Along (1, 0.3) the wavelength is 11.3 / √1.09 = 10.8 px: the 8–16 px band.
    const auto s = measure_spectrum(wave);
    REQUIRE(s);
    const double variance = amplitude * amplitude / 2;
    CHECK(s->band_variance[2] == Approx(variance).epsilon(0.05));
    for (int k : {0, 1, 3, 4, 5, 6}) CHECK(s->band_variance[static_cast<std::size_t>(k)] < 0.02 * variance);
}

TEST_CASE("image spectrum: white noise is flat, every band holding its share of the frequency plane", "[synth][stats]") {
    const double sigma = 5.0;
    const auto s = measure_spectrum(white_noise(sigma, 7));
    REQUIRE(s);
    CHECK(std::abs(s->exponent) < 0.15);
    // Band k spans frequencies 2^-(k+2) to 2^-(k+1) cycles/px: an annulus of area 3π·2^-(2k+4) in the unit square.
    for (int k = 0; k < 3; ++k)
        CHECK(s->band_variance[static_cast<std::size_t>(k)] ==
              Approx(sigma * sigma * 3 * M_PI * std::pow(2.0, -(2 * k + 4))).epsilon(0.05));
}

TEST_CASE("image spectrum: the exponent of a 1/f^α field is α", "[synth][stats]") {
    for (double alpha : {1.0, 2.0, 3.0}) {
        const auto s = measure_spectrum(power_law_field(alpha, 11));
        REQUIRE(s);
        CHECK(s->exponent == Approx(alpha).margin(0.15));
    }
    // α = 2: every octave carries about the same variance (those the window's width leaves alone).
    const auto s = measure_spectrum(power_law_field(2.0, 13));
    REQUIRE(s);
    for (int k = 2; k < 5; ++k) CHECK(s->band_variance[static_cast<std::size_t>(k)] == Approx(s->band_variance[1]).epsilon(0.2));
}

TEST_CASE("image spectrum: blank or small images give none; colour images are refused", "[synth][stats]") {
    CHECK_FALSE(measure_spectrum(cv::Mat(480, 640, CV_8U, cv::Scalar(90))));
    CHECK_FALSE(measure_spectrum(white_noise(3, 1)(cv::Rect(0, 0, 90, 90))));
    CHECK_THROWS_AS(measure_spectrum(cv::Mat(480, 640, CV_8UC3, cv::Scalar(1, 2, 3))), std::invalid_argument);
    CHECK_THROWS_AS(measure_spectrum(cv::Mat(480, 640, CV_16U, cv::Scalar(1))), std::invalid_argument);
}
