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

cv::Mat register_depth(const cv::Mat& depth, const Intrinsics& d, const Intrinsics& c, const Eigen::Isometry3d& color_from_depth,
                       cv::Size size) {
    cv::Mat registered(size, CV_32FC1, cv::Scalar(0));
    const double half = 0.5 * (c.fx / d.fx) + 0.25;  // half the side of a depth pixel's square, colour px
    for (int v = 0; v < depth.rows; ++v)
        for (int u = 0; u < depth.cols; ++u) {
            const float z = depth.at<float>(v, u);
            if (!(z > 0)) continue;
            const Eigen::Vector3d X((u - d.cx) / d.fx * z, (v - d.cy) / d.fy * z, z);
            const Eigen::Vector3d Xc = color_from_depth * X;
            if (Xc.z() <= 0.05) continue;
            const Eigen::Vector2d p = project(c, Xc);
            const double h = half * z / Xc.z();
            const int u0 = std::max(0, static_cast<int>(std::ceil(p.x() - h))),
                      u1 = std::min(size.width - 1, static_cast<int>(std::floor(p.x() + h)));
            const int v0 = std::max(0, static_cast<int>(std::ceil(p.y() - h))),
                      v1 = std::min(size.height - 1, static_cast<int>(std::floor(p.y() + h)));
            const float zc = static_cast<float>(Xc.z());
            for (int y = v0; y <= v1; ++y)
                for (int x = u0; x <= u1; ++x) {
                    float& dst = registered.at<float>(y, x);
                    if (dst == 0 || zc < dst) dst = zc;
                }
        }
    return registered;
}

}  // namespace vobench::rgbd
