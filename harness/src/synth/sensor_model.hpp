// sensor_model.hpp — Kinect v1 (structured light) and Kinect v2 (time of flight), every parameter in
// one place with its source. The colour cameras use PUT's own calibration and camera-in-marker poses
// (PUTK² files camData.txt, cameraZnacznikKin1/2.txt; Kraft et al. 2016), so sequences can follow the
// real PUTK² ground truth.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <string>

namespace vobench::synth {

struct PinholeCamera {
    int width = 0, height = 0;
    double fx = 0, fy = 0, cx = 0, cy = 0;
    int distortion_count = 0;
    std::array<double, 8> distortion{};  // OpenCV rational model: k1 k2 p1 p2 k3 k4 k5 k6
};

enum class DepthPrinciple { StructuredLight, TimeOfFlight };

struct SensorModel {
    std::string name;  // "kinect1" | "kinect2"
    DepthPrinciple principle = DepthPrinciple::StructuredLight;
    PinholeCamera color;
    PinholeCamera depth;                 // native depth image (Kinect v1: registered grid, half colour res)
    Eigen::Isometry3d depth_in_color;    // pose of the depth camera in the colour camera frame
    Eigen::Isometry3d camera_in_marker;  // colour camera in the robot marker frame (eq. 10)
    double min_range_m = 0.5, max_range_m = 4.5;
    double glancing_limit_deg = 80.0;  // beyond this incidence angle no return
    double lateral_sigma_px = 0.3;     // jitter of the depth sampling position
    // Structured light (Khoshelham & Elberink 2012): z = f·b / d, disparity d quantised to 1/8 px.
    double ir_focal_px = 580.0;  // at the 640×480 IR resolution
    double baseline_m = 0.075;   // projector–IR camera
    double disparity_step_px = 0.125;
    double disparity_sigma_px = 0.0505;  // with the quantisation: σ_z ≈ 1.425e-3·z² m (their eq. 16 fit)
    Eigen::Vector3d projector_in_color{-0.05, 0.0, 0.0};
    // Time of flight (Fankhauser et al. 2015, axial noise fit, mm):
    //   σ_z(z, θ) = 1.5 − 0.5·z + 0.3·z² + 0.1·z^1.5·θ²/(π/2 − θ)²
    double flying_pixel_probability = 0.6;  // of a pixel at a depth discontinuity (> 5 cm step)
    double dropout_probability = 0.003;     // isolated invalid pixels
    // Colour camera exposure and noise.
    double exposure_s = 0.015;
    double color_noise_dn = 2.0;  // σ of additive noise, 8-bit digital numbers
    double gain = 1.0;
};

SensorModel kinect1();
SensorModel kinect2();
SensorModel sensor_by_name(const std::string& name);  // throws std::invalid_argument

// Kinect v1 axial noise model (Khoshelham & Elberink 2012), metres.
inline double kinect1_sigma_z(double z) { return 1.425e-3 * z * z; }
// Kinect v2 axial noise model (Fankhauser et al. 2015), metres; theta = incidence angle (rad).
double kinect2_sigma_z(double z, double theta);

}  // namespace vobench::synth
