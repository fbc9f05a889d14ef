// The `synth stats` statistic "depth noise on planes at grey-level edges ÷ away from them"
// (texture_edge_depth_noise.hpp), against planes and noise of known size.
#include "synth/texture_edge_depth_noise.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <random>

using namespace vobench;

namespace {

// A checkerboard of 8-px squares (grey 60 / 180): 3×3 Sobel magnitudes of 480 across its edges, 0 inside.
cv::Mat checkerboard(int w, int h) {
    cv::Mat g(h, w, CV_8UC1);
    for (int v = 0; v < h; ++v)
        for (int u = 0; u < w; ++u) g.at<uint8_t>(v, u) = ((u / 8 + v / 8) % 2) ? 180 : 60;
    return g;
}

// A tilted plane about 2 m away with Gaussian noise σ, `edge_factor` times σ on the grey image's edges.
cv::Mat noisy_plane(const cv::Mat& grey, double sigma_m, double edge_factor, unsigned seed) {
    cv::Mat gx, gy, magnitude;
    cv::Sobel(grey, gx, CV_32F, 1, 0);
    cv::Sobel(grey, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, magnitude);
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 1.0);
    cv::Mat z(grey.size(), CV_32FC1);
    for (int v = 0; v < z.rows; ++v)
        for (int u = 0; u < z.cols; ++u) {
            const double s = magnitude.at<float>(v, u) > 40 ? edge_factor * sigma_m : sigma_m;
            z.at<float>(v, u) = static_cast<float>(2.0 + 0.001 * u - 0.0005 * v + s * noise(rng));
        }
    return z;
}

}  // namespace

TEST_CASE("patch plane: an exact plane is fitted exactly; a missing pixel gives none", "[synth][stats]") {
    cv::Mat z(40, 40, CV_32FC1);
    for (int v = 0; v < 40; ++v)
        for (int u = 0; u < 40; ++u) z.at<float>(v, u) = static_cast<float>(2.0 + 0.01 * u - 0.005 * v);
    const auto p = synth::fit_patch_plane(z, 8, 4, 24);
    REQUIRE(p);
    CHECK(p->a == Approx(0.01).epsilon(1e-5));
    CHECK(p->b == Approx(-0.005).epsilon(1e-5));
    CHECK(p->c == Approx(2.0 + 0.01 * (8 + 11.5) - 0.005 * (4 + 11.5)).epsilon(1e-6));  // the value at the patch's centre
    CHECK(p->rms < 1e-6);
    z.at<float>(10, 10) = 0;
    CHECK_FALSE(synth::fit_patch_plane(z, 8, 4, 24));
}

TEST_CASE("texture-edge depth noise: 1 where the noise ignores the texture, the factor where it follows it", "[synth][stats]") {
    const cv::Mat grey = checkerboard(320, 240);
    // Mean |N(0, kσ)| / mean |N(0, σ)| = k; the plane fit takes 3 of 576 degrees of freedom per patch.
    const auto even = synth::texture_edge_depth_noise_ratio(noisy_plane(grey, 0.002, 1.0, 1), grey);
    REQUIRE(even);
    CHECK(*even == Approx(1.0).margin(0.05));
    const auto doubled = synth::texture_edge_depth_noise_ratio(noisy_plane(grey, 0.002, 2.0, 2), grey);
    REQUIRE(doubled);
    CHECK(*doubled == Approx(2.0).epsilon(0.05));
    // No texture edges: no statistic (not a ratio of 1).
    const cv::Mat blank(240, 320, CV_8UC1, cv::Scalar(128));
    CHECK_FALSE(synth::texture_edge_depth_noise_ratio(noisy_plane(blank, 0.002, 1.0, 3), blank));
    // Geometric steps in every patch (not planar): none either.
    cv::Mat steps = noisy_plane(grey, 0.002, 1.0, 4);
    for (int v = 0; v < steps.rows; ++v)
        for (int u = 0; u < steps.cols; ++u)
            if ((u % 24) >= 12) steps.at<float>(v, u) += 0.3f;
    CHECK_FALSE(synth::texture_edge_depth_noise_ratio(steps, grey));
}
