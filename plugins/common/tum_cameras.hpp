// tum_cameras.hpp — the TUM RGB-D benchmark's published colour camera calibrations (the data set's
// "file formats" page, Sturm et al. 2012): fr1, fr2 (both Kinect v1) and fr3 (an Asus Xtion whose
// images TUM stored already undistorted). Used by the tum reader (`intrinsics=fr1|fr2|fr3`) and by
// `vobench synth --camera tum-fr1|tum-fr2|tum-fr3`, so a rendered TUM trajectory and the real data
// are read through the same numbers. All images are 640×480.
#pragma once

namespace vobench::tum {

struct PublishedCamera {
    double fx, fy, cx, cy;
    double d[5];  // k1 k2 p1 p2 k3 (TUM's d0..d4, OpenCV's order)
};

inline constexpr int kImageWidth = 640, kImageHeight = 480;
inline constexpr PublishedCamera kFr1{517.3, 516.5, 318.6, 255.3, {0.2624, -0.9531, -0.0054, 0.0026, 1.1633}};
inline constexpr PublishedCamera kFr2{520.9, 521.0, 325.1, 249.7, {0.2312, -0.7849, -0.0033, -0.0001, 0.9172}};
inline constexpr PublishedCamera kFr3{535.4, 539.2, 320.1, 247.6, {0, 0, 0, 0, 0}};
// ROS's default for a Kinect v1 without calibration (TUM's recommendation for unknown sequences).
inline constexpr PublishedCamera kRosDefault{525.0, 525.0, 319.5, 239.5, {0, 0, 0, 0, 0}};

}  // namespace vobench::tum
