#include "synth/depth_noise_persistence.hpp"

#include "synth/depth_geometry.hpp"
#include "synth/texture_edge_depth_noise.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

namespace vobench::synth {
namespace {

constexpr int kPatch = 32;
constexpr double kNear = 0.8, kFar = 3.0, kPlanar = 0.02;

}  // namespace

std::optional<cv::Mat> scaled_plane_residuals(const cv::Mat& depth_m, int x, int y, int patch, double near, double far) {
    const std::optional<PatchPlane> plane = fit_patch_plane(depth_m, x, y, patch);
    if (!plane || plane->c < near || plane->c >= far || plane->rms > kPlanar * plane->c) return std::nullopt;
    cv::Mat r(patch, patch, CV_64F);
    for (int j = 0; j < patch; ++j)
        for (int i = 0; i < patch; ++i) r.at<double>(j, i) = depth_m.at<float>(y + j, x + i) - plane->at(i, j, patch);
    return cv::Mat(r / (plane->c * plane->c));
}

std::vector<NoisePersistence> same_pixel_noise_correlation(const std::vector<std::filesystem::path>& depth_paths,
                                                           const std::vector<int>& gaps, std::size_t max_pairs, double depth_scale) {
    std::map<std::size_t, cv::Mat> loaded;  // the images of the pairs at hand (a long folder's would not fit)
    cv::Size size;
    auto image = [&](std::size_t k) -> const cv::Mat& {
        auto it = loaded.find(k);
        if (it != loaded.end()) return it->second;
        cv::Mat d = read_depth_metres(depth_paths[k], depth_scale);
        if (size.empty()) size = d.size();
        if (d.size() != size) throw std::runtime_error(depth_paths[k].string() + ": not the size of the folder's first depth image");
        return loaded.emplace(k, std::move(d)).first->second;
    };
    std::vector<NoisePersistence> out;
    for (int gap : gaps) {
        NoisePersistence p;
        p.gap = gap;
        std::vector<double> correlations;
        const std::size_t g = static_cast<std::size_t>(std::max(gap, 1));
        const std::size_t starts = depth_paths.size() > g ? depth_paths.size() - g : 0;
        const std::size_t n = max_pairs > 0 ? std::min(max_pairs, starts) : starts;
        for (std::size_t s = 0; s < n; ++s) {
            const std::size_t k = n == starts ? s : s * starts / n;
            loaded.erase(loaded.begin(), loaded.lower_bound(k));  // pairs start at increasing k
            const cv::Mat& a = image(k);
            const cv::Mat& b = image(k + g);
            for (int y = 0; y + kPatch <= a.rows; y += kPatch)
                for (int x = 0; x + kPatch <= a.cols; x += kPatch) {
                    const auto ra = scaled_plane_residuals(a, x, y, kPatch, kNear, kFar);
                    if (!ra) continue;
                    const auto rb = scaled_plane_residuals(b, x, y, kPatch, kNear, kFar);
                    if (!rb) continue;
                    const double norms = std::sqrt(ra->dot(*ra) * rb->dot(*rb));
                    if (norms > 0) correlations.push_back(ra->dot(*rb) / norms);
                }
        }
        p.patches = correlations.size();
        p.correlation = std::numeric_limits<double>::quiet_NaN();
        if (!correlations.empty()) {
            const auto middle = correlations.begin() + static_cast<std::ptrdiff_t>(correlations.size() / 2);
            std::nth_element(correlations.begin(), middle, correlations.end());
            p.correlation = *middle;
        }
        out.push_back(p);
    }
    return out;
}

}  // namespace vobench::synth
