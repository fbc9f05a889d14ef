// image_spectrum.hpp — how an image's contrast is spread over scales: the grey image's power spectrum,
// summed in octave bands of wavelength, and the exponent of its fall-off.
//
// Natural images have power spectra that fall as 1/f^α with α ≈ 2 (Field 1987; van der Schaaf &
// van Hateren 1996, α = 1.88 ± 0.43 over 276 images), so every octave of wavelength carries about the
// same variance. The bands show where a rendering lacks contrast against real frames: at long
// wavelengths (light, large shapes), in the middle (texture) or at the shortest (edges, blur, noise) —
// which FAST corners and a tracker's precision alone cannot tell apart (issue #15; `vobench synth stats`).
#pragma once

#include <opencv2/core.hpp>

#include <array>
#include <optional>

namespace vobench::synth {

struct ImageSpectrum {
    // Variance (grey levels²) at wavelengths [2^(k+1), 2^(k+2)) px for k = 0..6: 2–4 px up to 128–256
    // px, by the frequency's magnitude; the spectrum's corners past 1/2 cycle a pixel (diagonal
    // wavelengths under 2 px) are left out.
    static constexpr int kBands = 7;
    std::array<double, kBands> band_variance{};
    // α of a least-squares fit of log power density against log frequency over the wavelengths 8–128 px
    // (below 8 px noise and blur take over, above 128 px the window's width).
    double exponent = 0;
};

// The spectrum of a grey image (8-bit or 32-bit float, one channel) over its interior `border` px in
// from each edge, its mean removed and a Hann window applied, the window's loss of energy corrected
// (a stationary image's bands then sum to its variance). Nothing when the interior is under 64×64 px;
// std::invalid_argument for an image that is not one channel of 8-bit or float.
std::optional<ImageSpectrum> measure_spectrum(const cv::Mat& grey, int border = 16);

}  // namespace vobench::synth
