// sensor_model.hpp — Kinect v1 (structured light) and Kinect v2 (time of flight), every parameter in
// one place with its source. The colour cameras use PUT's own calibration and camera-in-marker poses
// (PUTK² files camData.txt, cameraZnacznikKin1/2.txt; Kraft et al. 2016), so sequences can follow the
// real PUTK² ground truth.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace vobench::synth {

struct PinholeCamera {
    int width = 0, height = 0;
    double fx = 0, fy = 0, cx = 0, cy = 0;
    int distortion_count = 0;
    std::array<double, 8> distortion{};  // OpenCV rational model: k1 k2 p1 p2 k3 k4 k5 k6
};

// The terms of a low-order disparity field at pixel (u, v) of `camera`: r², x, y and 1, for the pixel's
// pinhole-normalised x = (u − cx) / fx, y = (v − cy) / fy (SensorModel::disparity_distortion_px weighs the
// first three; fits of such a field add the constant).
inline Eigen::Vector4d disparity_field_terms(const PinholeCamera& camera, double u, double v) {
    const double x = (u - camera.cx) / camera.fx, y = (v - camera.cy) / camera.fy;
    return {x * x + y * y, x, y, 1.0};
}

enum class DepthPrinciple { StructuredLight, TimeOfFlight };

// Every effect of the sensor models, each one switchable (`vobench synth --effects`), so that what each
// costs an algorithm can be measured. All on by default except stamp_offsets, which only applies to
// built-in trajectories (with --stamps the real stamps are used whatever it says), tone_curve,
// which matches the real frames' contrast but makes feature tracking easier than on them, and
// and mosaic_noise, which matches one noise statistic and overshoots another (docs/synthetic-sensors.md).
struct Effects {
    // Colour camera.
    bool motion_blur = true;      // integration over the exposure time
    bool optics_blur = true;      // lens and demosaicing point spread (Gaussian)
    bool image_noise = true;      // shot and read noise
    bool mosaic_noise = false;    // the noise added on the Bayer mosaic and interpolated with it (off: see docs/synthetic-sensors.md)
    bool smooth_noise = true;     // a second, spatially smooth part of the colour noise (Kinect v1: measured; docs/synthetic-sensors.md)
    bool vignetting = true;       // radial fall-off of the lens
    bool auto_exposure = true;    // a gain that follows the scene's brightness with a lag
    bool tone_curve = false;      // the camera's contrast boost in display space (off: see docs/synthetic-sensors.md)
    bool highlights = true;       // specular reflection on glossy materials
    bool rolling_shutter = true;  // rows exposed one after another while the camera moves
    // Depth.
    bool depth_noise = true;             // the sensor's axial and lateral noise (and Kinect v1's quantisation)
    bool correlated_depth_noise = true;  // Kinect v1: disparity errors that are smooth across the image
    bool fixed_pattern_noise = true;     // Kinect v1: part of a pixel's disparity error repeats from frame to frame
    bool disparity_pattern = true;       // Kinect v1: the unit's fixed disparity error, smooth over the image
    bool projector_shadow = true;        // Kinect v1: no depth where the projector's pattern cannot reach
    bool depth_border = true;            // Kinect v1: the registered depth image's unmeasured border
    bool dark_dropout = true;            // lost returns on dark, glossy and glass surfaces
    bool glancing_dropout = true;        // no return beyond the glancing-angle limit
    bool far_dropout = true;             // Kinect v1: returns thin out with range before the limit
    bool edge_dropout = true;            // Kinect v1: the correlation window fails across depth steps
    bool flying_pixels = true;           // Kinect v2: mixed depths at discontinuities
    bool registration_error = true;      // Kinect v1: depth registered a little off the colour image
    bool stamp_offsets = false;          // built-in trajectories: depth stamps off the colour stamps
    bool stamp_latency = true;           // --stamps: each image exposed its stream's latency before its recorded stamp
    bool stamp_jitter = true;            // --stamps: exposed on the camera's regular clock, about which the recorded stamps jitter
    bool depth_distortion = true;        // Kinect v1: the camera's measured disparity offset field (none: nothing to add)
    // Trajectory files: the camera moves along the file's smoothed path, the file (with its motion
    // capture's noise) stays the reference (measured_path.hpp).
    bool measured_reference = true;
    // TUM-format camera trajectory files: the reference written describes a frame turned from the
    // rendered camera's by the camera's measured SensorModel::reference_turn_deg (reference_frame_error.hpp).
    bool reference_frame_error = true;
};

// Parses "all", "none", or a comma list of [+|-]name applied to the defaults (e.g. "-motion_blur" or
// "none,+depth_noise"); throws std::invalid_argument naming an unknown effect and listing the names.
Effects parse_effects(const std::string& spec);
std::vector<std::pair<std::string, bool>> effect_list(const Effects& e);  // name, on — for synth.json

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
    // The per-pixel disparity noise above (effect depth_noise) as a block matcher makes it: the average
    // of independent draws over this window (a box, pixels of a 640-wide image, odd), rescaled to keep
    // σ per pixel, so neighbours within a window share most of their error. 0 or 1: independent
    // from pixel to pixel.
    double disparity_window_px = 0;
    // Effect fixed_pattern_noise: the share of that per-pixel draw's variance which repeats from frame
    // to frame while a pixel sees the same disparity (the projector's speckle its window sees is the
    // same), drifting to a new draw over disparity_fixed_length_px of disparity change (pixels of the
    // 640-wide IR image). 0: a new draw every frame.
    double disparity_fixed_share = 0.0;
    double disparity_fixed_length_px = 1.0;
    // Effect correlated_depth_noise: a smooth disparity error field, new each frame, of this σ and
    // correlation length (pixels of a 640-wide image) — the correlation window's errors are shared by
    // neighbouring pixels, so they do not average out over a surface (docs/synthetic-sensors.md).
    double disparity_correlated_sigma_px = 0.0;
    double disparity_correlation_px = 16.0;
    // Effect depth_distortion: a fixed disparity offset δ = a·r² + b·x + c·y (pixels of the 640-wide IR
    // image; x, y the depth grid's normalised pinhole coordinates, r² = x² + y²) added to every
    // measurement — the unit's own calibration error, whose depth error grows as z²·δ/(f·b)
    // (Herrera et al. 2012 model such a pattern; Teichman et al. 2013 show it differs from unit to
    // unit). Zero unless the camera (`--camera`) brings a measured one.
    std::array<double, 3> disparity_distortion_px{};
    // Effect disparity_pattern: beyond that low-order field, every Kinect v1 unit adds a fixed disparity
    // error that varies over the image in blobs of about a hundred pixels (Smisek et al. 2011 and
    // Herrera et al. 2012 show such residual patterns; disparity_pattern.hpp measures it): a smooth
    // random field of this σ and lattice spacing (pixels of a 640-wide image), the same in every frame
    // of a rendering and drawn anew for each seed (another unit). 0: none.
    double disparity_pattern_sigma_px = 0.0;
    double disparity_pattern_length_px = 100.0;
    Eigen::Vector3d projector_in_color{-0.05, 0.0, 0.0};
    // Kinect v1: the correlation window that straddles an occluder's edge still matches the occluder's
    // pattern, so its depth runs on this far (pixels of a 640-wide image) into the projector's shadow
    // beside it (foreground fattening); only wider shadows stay holes. 0: the geometric shadow.
    int shadow_fill_px = 0;
    // Time of flight (Fankhauser et al. 2015, axial noise fit, mm):
    //   σ_z(z, θ) = 1.5 − 0.5·z + 0.3·z² + 0.1·z^1.5·θ²/(π/2 − θ)²
    double flying_pixel_probability = 0.6;  // of a pixel at a depth discontinuity (> 5 cm step)
    double dropout_probability = 0.003;     // isolated invalid pixels
    // Failures of the returns (both sensors; sources in sensor_model.cpp).
    double dark_albedo = 0.08;              // returns are lost in blobs on surfaces darker than this (linear albedo)
    double dark_dropout_max = 0.3;          // ... with this probability on black
    double gloss_dropout = 0.25;            // share of a glossy surface's returns lost (× gloss)
    double dropout_blob_m = 0.02;           // size of the lost-return blobs on the surface
    double far_dropout_start_m = 3.5;       // Kinect v1: dropout rises linearly from here to max_range_m
    double edge_dropout_probability = 0.5;  // Kinect v1: at a depth step over 5 % of the range
    // Kinect v1: a disparity is matched over a correlation window, so a return is lost (dark, glossy,
    // far, at a depth step) where most of the window's returns are: the lost-return mask is a majority
    // vote over this window (pixels of a 640-wide image; 1: each pixel alone).
    int dropout_window_px = 1;
    // Kinect v1's registered depth border in pixels of a 640×480 colour image (scaled with its width):
    // left f·b_IR/z (IR–colour parallax), right, top and bottom fixed.
    // Kinect v1's registration error: the depth image's content lies this far right and down of the
    // colour image's, pixels of a 640-wide image.
    Eigen::Vector2d registration_shift_px{1.5, 2.0};
    double border_left_px_m = 13.0, border_right_px = 40, border_top_px = 34, border_bottom_px = 3;
    // Colour camera exposure and noise.
    double exposure_s = 0.015;
    double color_noise_dn = 2.0;            // σ of additive noise, 8-bit digital numbers
    double mosaic_noise_dn = 0;             // mosaic_noise: σ at each site of the RGGB mosaic (0: not measured, noise per pixel)
    double smooth_noise_dn = 0;             // smooth_noise: σ of the smooth part per channel (0: not measured, none)
    double smooth_noise_px = 1.0;           // ... and its Gaussian correlation length, px of a 640-wide image
    double optics_sigma_px = 0.6;           // Gaussian point spread of lens and demosaicing (Kinect v2: assumed)
    double vignetting = 0.25;               // relative brightness loss in the image corners (∝ r²)
    double exposure_target = 0.34;          // auto-exposure: linear mean luminance aimed at (sRGB ≈ 157)
    double exposure_time_constant_s = 0.3;  // ... and how fast it follows the scene (assumed; Kinect v1: measured)
    // The camera's tone curve beyond sRGB (effect tone_curve): display values stretched about the real
    // frames' mean grey g = 136/255, y' = g + tone_contrast·(y − g), clipped to [0, 1] (consumer cameras
    // boost contrast; Grossberg & Nayar 2004 measured such S-shaped responses). 1: plain sRGB.
    double tone_contrast = 1.0;
    double gain = 1.0;
    double color_readout_s = 0.0, depth_readout_s = 0.0;  // rolling shutter: first to last row
    // Effect stamp_latency (with real stamps, `--stamps`): how long before its recorded stamp each
    // stream's image is exposed (its middle row). Recorded stamps are when the driver received an image.
    double color_latency_s = 0.0, depth_latency_s = 0.0;
    // The turn between the frame the camera's real reference describes and its optical frame (effect
    // reference_frame_error), a rotation vector in camera axes, degrees: the colour camera's
    // (CameraSpec::reference_turn_deg, set by with_color_camera; zero where none was measured).
    std::array<double, 3> reference_turn_deg{};
    Effects effects;
};

SensorModel kinect1();
SensorModel kinect2();
SensorModel sensor_by_name(const std::string& name);  // throws std::invalid_argument

// Kinect v1 axial noise model (Khoshelham & Elberink 2012), metres.
inline double kinect1_sigma_z(double z) { return 1.425e-3 * z * z; }
// Kinect v2 axial noise model (Fankhauser et al. 2015), metres; theta = incidence angle (rad).
double kinect2_sigma_z(double z, double theta);

}  // namespace vobench::synth
