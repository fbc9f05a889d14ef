#include "synth/texture_edge_depth_noise.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>

namespace vobench::synth {
namespace {
constexpr int kPatch = 24;
constexpr double kPlanarRms = 0.01;  // of the depth: planar, no geometric edge in the patch
constexpr float kEdge = 40.0f, kFlat = 10.0f;
constexpr std::size_t kMinPixels = 200;
}  // namespace

std::optional<PatchPlane> fit_patch_plane(const cv::Mat& depth_m, int x, int y, int patch) {
    // Centred coordinates make the normal equations diagonal: a = Σ(i·z)/Σi², b = Σ(j·z)/Σj², c = mean.
    double sum_i2 = 0;
    for (int i = 0; i < patch; ++i) sum_i2 += (i - (patch - 1) / 2.0) * (i - (patch - 1) / 2.0);
    sum_i2 *= patch;
    double sz = 0, siz = 0, sjz = 0;
    for (int j = 0; j < patch; ++j)
        for (int i = 0; i < patch; ++i) {
            const float z = depth_m.at<float>(y + j, x + i);
            if (z <= 0) return std::nullopt;
            sz += z;
            siz += (i - (patch - 1) / 2.0) * z;
            sjz += (j - (patch - 1) / 2.0) * z;
        }
    PatchPlane p;
    p.c = sz / (patch * patch);
    p.a = siz / sum_i2;
    p.b = sjz / sum_i2;
    double ss = 0;
    for (int j = 0; j < patch; ++j)
        for (int i = 0; i < patch; ++i) {
            const double r = depth_m.at<float>(y + j, x + i) - p.at(i, j, patch);
            ss += r * r;
        }
    p.rms = std::sqrt(ss / (patch * patch - 3));
    return p;
}

std::optional<double> texture_edge_depth_noise_ratio(const cv::Mat& depth_m, const cv::Mat& grey) {
    cv::Mat gx, gy, magnitude;
    cv::Sobel(grey, gx, CV_32F, 1, 0);
    cv::Sobel(grey, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, magnitude);
    double edge_sum = 0, flat_sum = 0;
    std::size_t edge_n = 0, flat_n = 0;
    // Patches start 1 px in, so the 3×3 Sobel never reads past the image.
    for (int y = 1; y + kPatch < depth_m.rows; y += kPatch)
        for (int x = 1; x + kPatch < depth_m.cols; x += kPatch) {
            const std::optional<PatchPlane> plane = fit_patch_plane(depth_m, x, y, kPatch);
            if (!plane || plane->rms > kPlanarRms * plane->c) continue;
            for (int j = 0; j < kPatch; ++j)
                for (int i = 0; i < kPatch; ++i) {
                    const float m = magnitude.at<float>(y + j, x + i);
                    const double r = std::abs(depth_m.at<float>(y + j, x + i) - plane->at(i, j, kPatch)) / plane->c;
                    if (m > kEdge) {
                        edge_sum += r;
                        ++edge_n;
                    } else if (m < kFlat) {
                        flat_sum += r;
                        ++flat_n;
                    }
                }
        }
    if (edge_n < kMinPixels || flat_n < kMinPixels || flat_sum <= 0) return std::nullopt;
    return (edge_sum / static_cast<double>(edge_n)) / (flat_sum / static_cast<double>(flat_n));
}

}  // namespace vobench::synth
