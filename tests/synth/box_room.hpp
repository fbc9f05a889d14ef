// box_room.hpp — a test scene: an axis-aligned box room [-2, 2] × [-1.2, 1.3] × [-3, 3] ray-cast through
// a camera's ray model (its distortion included), with smoothly textured walls, for the statistics of
// `vobench synth stats --camera` that need exact depth and poses.
#pragma once

#include "synth/depth_geometry.hpp"

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <cmath>
#include <limits>

namespace vobench::test {

// A small camera (320×240) with a lens like TUM's, so that the ray model's distortion matters.
inline synth::PinholeCamera small_distorted_camera() {
    synth::PinholeCamera c;
    c.width = 320;
    c.height = 240;
    c.fx = c.fy = 260.0;
    c.cx = 159.5;
    c.cy = 119.5;
    c.distortion_count = 5;
    c.distortion = {0.12, -0.2, 0.001, -0.002, 0.05, 0, 0, 0};
    return c;
}

struct BoxRoomView {
    cv::Mat depth;  // metres along the optical axis, CV_32F
    cv::Mat grey;   // CV_8U: the walls' texture, a few sinusoids of the hit point (ample gradient)
};

// The room seen from `pose` (camera-to-room); `single_wall` keeps only the wall z = 3.
inline BoxRoomView box_room_view(const synth::DepthRays& rays, const Eigen::Isometry3d& pose, bool single_wall = false) {
    const auto& c = rays.camera();
    BoxRoomView view{cv::Mat(c.height, c.width, CV_32F, cv::Scalar(0)), cv::Mat(c.height, c.width, CV_8U, cv::Scalar(0))};
    const double lo[3] = {-2.0, -1.2, -3.0}, hi[3] = {2.0, 1.3, 3.0};
    for (int v = 0; v < c.height; ++v)
        for (int u = 0; u < c.width; ++u) {
            const Eigen::Vector3d d = pose.linear() * rays.point(u, v, 1.0), o = pose.translation();
            double t = std::numeric_limits<double>::infinity();
            for (int a = 0; a < 3; ++a)
                for (double plane : {lo[a], hi[a]}) {
                    if ((single_wall && !(a == 2 && plane == hi[2])) || std::abs(d[a]) < 1e-12) continue;
                    const double s = (plane - o[a]) / d[a];
                    if (s > 0) t = std::min(t, s);
                }
            if (!std::isfinite(t)) continue;
            view.depth.at<float>(v, u) = static_cast<float>(t);  // the ray has z = 1: t is the depth
            const Eigen::Vector3d p = o + t * d;
            const double shade =
                128 + 45 * std::sin(9 * p.x() + 2 * p.y()) * std::sin(7 * p.z() - 3 * p.y()) + 35 * std::sin(17 * (p.x() + p.y() + p.z()));
            view.grey.at<uchar>(v, u) = cv::saturate_cast<uchar>(shade);
        }
    return view;
}

}  // namespace vobench::test
