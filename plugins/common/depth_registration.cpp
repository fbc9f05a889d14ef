#include "depth_registration.hpp"

#include <algorithm>
#include <cmath>

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

cv::Mat DepthRegistration::operator()(const cv::Mat& depth) const {
    CV_Assert(depth.type() == CV_32FC1 && depth.size() == depth_size_);
    cv::Mat registered(color_size_, CV_32FC1, cv::Scalar(0));
    for (int v = 0; v < depth.rows; ++v) {
        const float* row = depth.ptr<float>(v);
        const Eigen::Vector3d* ray = &rays_[static_cast<std::size_t>(v) * depth.cols];
        for (int u = 0; u < depth.cols; ++u) {
            const float z = row[u];
            if (!(z > 0)) continue;
            const Eigen::Vector3d Xc = static_cast<double>(z) * ray[u] + translation_;
            if (Xc.z() <= 0.05) continue;
            const Eigen::Vector2d p = project(color_, Xc);
            const double h = half_ * z / Xc.z();  // the square shrinks with distance from the colour camera
            const int u0 = std::max(0, static_cast<int>(std::ceil(p.x() - h))),
                      u1 = std::min(color_size_.width - 1, static_cast<int>(std::floor(p.x() + h)));
            const int v0 = std::max(0, static_cast<int>(std::ceil(p.y() - h))),
                      v1 = std::min(color_size_.height - 1, static_cast<int>(std::floor(p.y() + h)));
            const float zc = static_cast<float>(Xc.z());
            for (int y = v0; y <= v1; ++y) {
                float* dst = registered.ptr<float>(y);
                for (int x = u0; x <= u1; ++x)
                    if (dst[x] == 0 || zc < dst[x]) dst[x] = zc;
            }
        }
    }
    return registered;
}

cv::Mat register_depth(const cv::Mat& depth, const Intrinsics& d, const Intrinsics& c, const Eigen::Isometry3d& color_from_depth,
                       cv::Size size) {
    return DepthRegistration(d, c, color_from_depth, depth.size(), size)(depth);
}

}  // namespace vobench::rgbd
