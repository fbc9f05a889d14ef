// The Kinect v2 depth-to-colour registration (plugins/common/depth_registration.hpp): it projects in
// parallel and fills bands of colour rows in parallel; the image must be the one a plain pass over the
// depth pixels in order gives, written out here, whatever the number of threads.
#include "depth_registration.hpp"

#include <catch2/catch.hpp>
#include <opencv2/core/utility.hpp>

#include <cmath>
#include <random>

namespace {

using vobench::rgbd::DepthRegistration;
using vobench::rgbd::Intrinsics;

// The rule of the header, one depth pixel after another: the pixel's square (side c.fx / d.fx at
// the depth camera, shrinking with distance from the colour camera) around its projection, nearest
// depth first.
cv::Mat register_in_order(const cv::Mat& depth, const Intrinsics& d, const Intrinsics& c, const Eigen::Isometry3d& color_from_depth,
                          cv::Size size) {
    cv::Mat out(size, CV_32FC1, cv::Scalar(0));
    const double half = 0.5 * (c.fx / d.fx) + 0.25;
    for (int v = 0; v < depth.rows; ++v)
        for (int u = 0; u < depth.cols; ++u) {
            const float z = depth.at<float>(v, u);
            if (!(z > 0)) continue;
            const Eigen::Vector3d ray = color_from_depth.linear() * Eigen::Vector3d((u - d.cx) / d.fx, (v - d.cy) / d.fy, 1.0);
            const Eigen::Vector3d X = static_cast<double>(z) * ray + color_from_depth.translation();
            if (X.z() <= 0.05) continue;
            const Eigen::Vector2d p = vobench::rgbd::project(c, X);
            const double h = half * z / X.z();
            const float zc = static_cast<float>(X.z());
            for (int y = static_cast<int>(std::ceil(p.y() - h)); y <= static_cast<int>(std::floor(p.y() + h)); ++y)
                for (int x = static_cast<int>(std::ceil(p.x() - h)); x <= static_cast<int>(std::floor(p.x() + h)); ++x) {
                    if (x < 0 || y < 0 || x >= size.width || y >= size.height) continue;
                    float& dst = out.at<float>(y, x);
                    if (dst == 0 || zc < dst) dst = zc;
                }
        }
    return out;
}

}  // namespace

TEST_CASE("depth registration: the plain in-order z-buffer, on any number of threads", "[datasets][registration]") {
    // A small Kinect v2-like pair: the colour camera ~3x finer, with lens distortion, 5 cm beside.
    Intrinsics d{73.1, 73.1, 51.5, 42.5, 0, {}};
    Intrinsics c{215.7, 215.3, 190.5, 106.1, 8, {0.027, -0.0039, -0.00038, -0.0024, 0.059, -0.029, 0.059, 0.039}};
    Eigen::Isometry3d color_from_depth = Eigen::Isometry3d::Identity();
    color_from_depth.linear() = Eigen::AngleAxisd(0.02, Eigen::Vector3d(0.3, 1, 0.1).normalized()).toRotationMatrix();
    color_from_depth.translation() = Eigen::Vector3d(0.052, 0.001, -0.002);
    const cv::Size depth_size(104, 85), color_size(384, 216);

    // Steps between near and far surfaces (occlusions), holes, and a few points behind the colour camera.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    cv::Mat depth(depth_size, CV_32FC1);
    for (int v = 0; v < depth.rows; ++v)
        for (int u = 0; u < depth.cols; ++u) {
            const float r = uniform(rng);
            depth.at<float>(v, u) = r < 0.1f ? 0.0f : r < 0.12f ? -1.0f : ((u / 9 + v / 7) % 3 == 0 ? 0.6f : 2.5f) + 0.3f * uniform(rng);
        }

    const cv::Mat expected = register_in_order(depth, d, c, color_from_depth, color_size);
    REQUIRE(cv::countNonZero(expected) > color_size.area() / 2);
    const DepthRegistration registration(d, c, color_from_depth, depth_size, color_size);
    const int threads = cv::getNumThreads();
    for (int n : {1, 2, 5}) {
        cv::setNumThreads(n);
        const cv::Mat got = registration(depth);
        REQUIRE(got.size() == color_size);
        REQUIRE(got.type() == CV_32FC1);
        CHECK(cv::countNonZero(got != expected) == 0);
    }
    cv::setNumThreads(threads);
}
