// rgbd_frame.hpp — what odometry plugins do with a vobench_frame: view its pixels as cv::Mat without
// copying, get grey levels, look up metric depth robustly, back-project pixels, and write an Eigen
// pose into the ABI's pose struct.
#pragma once

#include <vobench/vobench_plugin.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include <vector>

namespace vobench::rgbd {

// A header over the borrowed pixels (nothing copied); throws vobench::sdk::Error on an unknown format.
cv::Mat wrap(const vobench_image& image);

// 8-bit grey from any colour format.
void to_gray(const vobench_image& image, cv::Mat& gray);

struct DepthRange {
    double min_m = 0.1, max_m = 6.0;
    bool interpolate = false;  // bilinear at the sub-pixel position instead of the nearest pixel's depth
};

// Metric depth at the nearest pixel, or NaN: missing, out of range, or on a depth edge (the 3×3
// neighbourhood spreads by more than 5 % of the depth — where holes and flying pixels live).
double depth_at(const cv::Mat& depth, double scale, const cv::Point2f& pixel, const DepthRange& range);

// Camera-frame 3-D points of (distorted) pixels: undistorted with K and `distortion`, times depth.
// NaN where depth_at() is NaN.
std::vector<Eigen::Vector3d> back_project(const cv::Mat& depth, double scale, const std::vector<cv::Point2f>& pixels, const cv::Matx33d& K,
                                          const cv::Mat& distortion, const DepthRange& range);

// Where a feature seen at `pixel` was when the frame's middle row was exposed. A rolling shutter
// reads row v out (v / rows − ½)·readout_s after the middle row (the renderer's model, and the real
// Kinect colour camera's: docs/synthetic-sensors.md); in that time the feature moved that share of its
// image motion `flow`, measured over the last `interval_s`. Constant image velocity: Kerl et al. (2015)
// model the same readout for RGB-D odometry with a continuous-time camera pose; a feature's own flow
// needs no pose and carries its parallax. The pixel unchanged when readout_s or interval_s is 0.
cv::Point2f at_middle_row(const cv::Point2f& pixel, const cv::Point2f& flow, int rows, double readout_s, double interval_s);

// K and distortion coefficients of an ABI camera.
cv::Matx33d camera_matrix(const vobench_camera& camera);
cv::Mat distortion_of(const vobench_camera& camera);

void write_pose(const Eigen::Isometry3d& world_from_camera, vobench_pose& pose);

}  // namespace vobench::rgbd
