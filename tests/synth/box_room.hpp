// box_room.hpp — a test scene: an axis-aligned box room [-2, 2] × [-1.2, 1.3] × [-3, 3] ray-cast through
// a camera's ray model (its distortion included), with smoothly textured walls, for the statistics of
// `vobench synth stats --camera` that need exact depth and poses.
#pragma once

#include "metrics/pose.hpp"
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

// A camera in the room swinging in yaw and pitch at up to ≈ 1 rad/s (fr1/rpy's fast part: 2–4° a
// frame) and drifting slowly, at time t.
inline Eigen::Isometry3d swinging_pose(double t) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.linear() = (Eigen::AngleAxisd(0.16 * std::sin(2 * M_PI * 0.9 * t), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(0.10 * std::sin(2 * M_PI * 1.3 * t + 0.5), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    p.translation() = Eigen::Vector3d(0.05 * t, 0.02 * std::sin(3 * t), 0.03 * t);
    return p;
}

// Its reference: the poses at 100 Hz over [from, to], as a motion-capture system records them.
inline metrics::Trajectory swinging_reference(double from, double to) {
    metrics::Trajectory out;
    for (double t = from; t <= to; t += 0.01) {
        metrics::StampedPose p;
        p.t = t;
        p.p = swinging_pose(t).translation();
        p.q = Eigen::Quaterniond(swinging_pose(t).linear());
        out.push_back(p);
    }
    return out;
}

}  // namespace vobench::test
