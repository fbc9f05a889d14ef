// putk2_files.hpp — the PUTK² calibration files (Kraft et al. 2016; PUT's tools):
//   camData.txt        `id, fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6` (OpenCV rational model, the
//                      model of the paper's eqs. 1–8), one camera per line;
//   depth_camera.txt   `fx fy cx cy` of the Kinect v2 depth camera, then its pose in the colour camera
//                      frame `x y z qw qx qy qz` (vobench's file; PUT's data ships registered depth);
//   matched.txt        `frame rgb_file depth_file` per line.
// Every parser names the file and line of what it cannot read.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <string>
#include <vector>

namespace vobench::putk2 {

struct CameraCalibration {
    std::string id;
    double fx = 0, fy = 0, cx = 0, cy = 0;
    std::array<double, 8> distortion{};
};

std::vector<CameraCalibration> parse_cam_data(const std::string& text, const std::string& name);

struct DepthCamera {
    double fx = 0, fy = 0, cx = 0, cy = 0;
    Eigen::Isometry3d in_color = Eigen::Isometry3d::Identity();
};

DepthCamera parse_depth_camera(const std::string& text, const std::string& name);

struct MatchedFrame {
    long long id;
    std::string color, depth;
};

std::vector<MatchedFrame> parse_matched(const std::string& text, const std::string& name);

}  // namespace vobench::putk2
