#include "depth_registration.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core/utility.hpp>

namespace vobench::rgbd {

Eigen::Vector2d project(const Intrinsics& c, const Eigen::Vector3d& p) {
    const double x = p.x() / p.z(), y = p.y() / p.z();
    const auto& k = c.distortion;
    const double r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
    const double radial = (1 + k[0] * r2 + k[1] * r4 + k[4] * r6) / (1 + k[5] * r2 + k[6] * r4 + k[7] * r6);
    const double xd = x * radial + 2 * k[2] * x * y + k[3] * (r2 + 2 * x * x);
    const double yd = y * radial + k[2] * (r2 + 2 * y * y) + 2 * k[3] * x * y;
    return {c.fx * xd + c.cx, c.fy * yd + c.cy};
}

DepthRegistration::DepthRegistration(const Intrinsics& d, const Intrinsics& c, const Eigen::Isometry3d& color_from_depth,
                                     cv::Size depth_size, cv::Size color_size)
    : color_(c),
      translation_(color_from_depth.translation()),
      depth_size_(depth_size),
      color_size_(color_size),
      half_(0.5 * (c.fx / d.fx) + 0.25),
      rays_(static_cast<std::size_t>(depth_size.area())) {
    const Eigen::Matrix3d R = color_from_depth.linear();
    for (int v = 0; v < depth_size.height; ++v)
        for (int u = 0; u < depth_size.width; ++u)
            rays_[static_cast<std::size_t>(v) * depth_size.width + u] = R * Eigen::Vector3d((u - d.cx) / d.fx, (v - d.cy) / d.fy, 1.0);
}

namespace {

// The colour pixels one depth pixel's square covers, and its depth there; empty when v0 > v1.
struct Splat {
    int u0 = 0, u1 = -1, v0 = 0, v1 = -1;
    float z = 0;
};

// Colour rows are filled in this many bands, each by one task.
constexpr int kBands = 16;

}  // namespace

cv::Mat DepthRegistration::operator()(const cv::Mat& depth) const {
    CV_Assert(depth.type() == CV_32FC1 && depth.size() == depth_size_);
    // First each depth pixel's square (the projection is the costly part), rows in parallel; then the
    // nearest depth in every colour pixel. The nearest of a set does not depend on the order it is
    // met in, so bands of colour rows are filled in parallel, each from the depth rows that reach it:
    // the same image as one pass in order.
    std::vector<Splat> splats(depth.total());
    std::vector<int> row_top(static_cast<std::size_t>(depth.rows)), row_bottom(static_cast<std::size_t>(depth.rows));
    cv::parallel_for_(cv::Range(0, depth.rows), [&](const cv::Range& rows) {
        for (int v = rows.start; v < rows.end; ++v) {
            const float* row = depth.ptr<float>(v);
            const Eigen::Vector3d* ray = &rays_[static_cast<std::size_t>(v) * depth.cols];
            Splat* out = &splats[static_cast<std::size_t>(v) * depth.cols];
            int top = color_size_.height, bottom = -1;
            for (int u = 0; u < depth.cols; ++u) {
                const float z = row[u];
                if (!(z > 0)) continue;
                const Eigen::Vector3d Xc = static_cast<double>(z) * ray[u] + translation_;
                if (Xc.z() <= 0.05) continue;
                const Eigen::Vector2d p = project(color_, Xc);
                const double h = half_ * z / Xc.z();  // the square shrinks with distance from the colour camera
                Splat& s = out[u];
                s.u0 = std::max(0, static_cast<int>(std::ceil(p.x() - h)));
                s.u1 = std::min(color_size_.width - 1, static_cast<int>(std::floor(p.x() + h)));
                s.v0 = std::max(0, static_cast<int>(std::ceil(p.y() - h)));
                s.v1 = std::min(color_size_.height - 1, static_cast<int>(std::floor(p.y() + h)));
                s.z = static_cast<float>(Xc.z());
                if (s.v0 <= s.v1 && s.u0 <= s.u1) top = std::min(top, s.v0), bottom = std::max(bottom, s.v1);
            }
            row_top[static_cast<std::size_t>(v)] = top;
            row_bottom[static_cast<std::size_t>(v)] = bottom;
        }
    });
    cv::Mat registered(color_size_, CV_32FC1, cv::Scalar(0));
    const int band_height = (color_size_.height + kBands - 1) / kBands;
    cv::parallel_for_(cv::Range(0, kBands), [&](const cv::Range& bands) {
        for (int b = bands.start; b < bands.end; ++b) {
            const int first = b * band_height, last = std::min(color_size_.height, first + band_height) - 1;
            for (int v = 0; v < depth.rows; ++v) {
                if (row_bottom[static_cast<std::size_t>(v)] < first || row_top[static_cast<std::size_t>(v)] > last) continue;
                const Splat* row = &splats[static_cast<std::size_t>(v) * depth.cols];
                for (int u = 0; u < depth.cols; ++u) {
                    const Splat& s = row[u];
                    for (int y = std::max(s.v0, first); y <= std::min(s.v1, last); ++y) {
                        float* dst = registered.ptr<float>(y);
                        for (int x = s.u0; x <= s.u1; ++x)
                            if (dst[x] == 0 || s.z < dst[x]) dst[x] = s.z;
                    }
                }
            }
        }
    });
    return registered;
}

}  // namespace vobench::rgbd
