#include "synth/image_spectrum.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vobench::synth {
namespace {

// The exponent's fit: rings of a quarter octave between these wavelengths.
constexpr double kFitShortestPx = 8, kFitLongestPx = 128;
constexpr int kRingsPerOctave = 4;
constexpr int kFitRings = 16;  // log2(128 / 8) octaves

// Signed frequency of DFT bin i of n, cycles per pixel.
double frequency(int i, int n) { return static_cast<double>(i <= n / 2 ? i : i - n) / n; }

}  // namespace

std::optional<ImageSpectrum> measure_spectrum(const cv::Mat& grey, int border) {
    if (grey.channels() != 1 || (grey.depth() != CV_8U && grey.depth() != CV_32F))
        throw std::invalid_argument("measure_spectrum: the image must be one channel of 8-bit or float");
    if (border < 0 || grey.cols - 2 * border < 64 || grey.rows - 2 * border < 64) return std::nullopt;
    cv::Mat x;
    grey(cv::Rect(border, border, grey.cols - 2 * border, grey.rows - 2 * border)).convertTo(x, CV_64F);
    x -= cv::mean(x)[0];
    cv::Mat window;
    cv::createHanningWindow(window, x.size(), CV_64F);
    x = x.mul(window);
    // Parseval for the unnormalised DFT: Σ|F|² = N·Σ|x|². The window keeps mean(w²) of a stationary
    // image's energy, so Σ_band |F|² / (N² · mean(w²)) is the band's share of the image's variance.
    const double n = static_cast<double>(x.total());
    const double normaliser = n * n * cv::mean(window.mul(window))[0];
    cv::Mat spectrum;
    cv::dft(x, spectrum, cv::DFT_COMPLEX_OUTPUT);

    ImageSpectrum out;
    std::array<double, kFitRings> ring_power{}, ring_log_f{};
    std::array<std::size_t, kFitRings> ring_count{};
    for (int i = 0; i < spectrum.rows; ++i) {
        const double fy = frequency(i, spectrum.rows);
        const cv::Vec2d* row = spectrum.ptr<cv::Vec2d>(i);
        for (int j = 0; j < spectrum.cols; ++j) {
            const double f = std::hypot(frequency(j, spectrum.cols), fy);
            if (f <= 0 || f > 0.5) continue;
            const double power = (row[j][0] * row[j][0] + row[j][1] * row[j][1]) / normaliser;
            const double wavelength = 1.0 / f;
            const int band = static_cast<int>(std::floor(std::log2(wavelength))) - 1;
            if (band >= 0 && band < ImageSpectrum::kBands) out.band_variance[static_cast<std::size_t>(band)] += power;
            if (wavelength >= kFitShortestPx && wavelength < kFitLongestPx) {
                const int ring = std::min(kFitRings - 1, static_cast<int>(std::floor(kRingsPerOctave * std::log2(kFitLongestPx * f))));
                ring_power[static_cast<std::size_t>(ring)] += power;
                ring_log_f[static_cast<std::size_t>(ring)] += std::log(f);
                ++ring_count[static_cast<std::size_t>(ring)];
            }
        }
    }
    // log (mean power in the ring) against the ring's mean log frequency; α = −slope.
    double sx = 0, sy = 0, sxx = 0, sxy = 0, m = 0;
    for (int r = 0; r < kFitRings; ++r) {
        const auto k = static_cast<std::size_t>(r);
        if (ring_count[k] == 0 || ring_power[k] <= 0) continue;
        const double lx = ring_log_f[k] / static_cast<double>(ring_count[k]);
        const double ly = std::log(ring_power[k] / static_cast<double>(ring_count[k]));
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
        m += 1;
    }
    const double denominator = m * sxx - sx * sx;
    if (m < 3 || denominator <= 0) return std::nullopt;
    out.exponent = -(m * sxy - sx * sy) / denominator;
    return out;
}

}  // namespace vobench::synth
