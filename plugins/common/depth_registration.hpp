// depth_registration.hpp — depth from a separate depth camera (Kinect v2: 512×424 ToF) onto the
// colour camera's pixels (1920×1080, with lens distortion), z-buffered.
//
// Each depth pixel is a small square on the scene: its 3-D point is projected into the colour camera
// and fills the colour pixels its square covers, nearest depth first. The colour camera samples the
// scene ~3× finer than the depth camera; OpenCV contrib's registerDepth projects points only and
// leaves most colour pixels empty (measured on a synthetic Kinect v2 frame: 17% of the pixels filled,
// against 49% here, the rest being outside the depth camera's field of view). Both are offered by the
// putk2 reader; the generator uses this one, so a reader that registers the same way reproduces it.
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <array>
#include <vector>

namespace vobench::rgbd {

struct Intrinsics {
    double fx = 0, fy = 0, cx = 0, cy = 0;
    int distortion_count = 0;
    std::array<double, 8> distortion{};  // OpenCV rational model k1 k2 p1 p2 k3 k4 k5 k6
};

// Projects a camera-frame point (z > 0) to pixels with the rational distortion model.
Eigen::Vector2d project(const Intrinsics& camera, const Eigen::Vector3d& point);

// The registration of one camera pair, set up once: each depth pixel's viewing ray, already turned
// into the colour camera's axes, is a table entry, so a frame costs one multiply-add, one projection
// and one splat per depth pixel (a reader registers every frame of a sequence with the same pair).
class DepthRegistration {
public:
    DepthRegistration(const Intrinsics& depth_camera, const Intrinsics& color_camera, const Eigen::Isometry3d& color_from_depth,
                      cv::Size depth_size, cv::Size color_size);

    // `depth`: CV_32FC1 metres of depth_size in the (undistorted pinhole) depth camera; 0 = no reading.
    // Returns CV_32FC1 metres of color_size; 0 where nothing projects. Runs on OpenCV's threads
    // (cv::setNumThreads bounds them); the result does not depend on how many there are.
    cv::Mat operator()(const cv::Mat& depth) const;

private:
    Intrinsics color_;
    Eigen::Vector3d translation_;
    cv::Size depth_size_, color_size_;
    double half_ = 0;                    // half the side of a depth pixel's square at the depth camera, colour px
    std::vector<Eigen::Vector3d> rays_;  // R · ((u − cx)/fx, (v − cy)/fy, 1), row-major over the depth image
};

}  // namespace vobench::rgbd
