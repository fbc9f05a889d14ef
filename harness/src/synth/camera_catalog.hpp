// camera_catalog.hpp — colour cameras by name for `vobench synth --camera NAME|FILE`.
//
// Names: putk2-kinect1 and putk2-kinect2 (PUT's own calibrations, the sensors' defaults) and tum-fr1,
// tum-fr2, tum-fr3 (the TUM RGB-D benchmark's published intrinsics and distortion, 640×480), so a
// real TUM trajectory can be rendered through its own camera and read back with
// `--dataset tum --option intrinsics=fr1`.
//
// A FILE holds one line `width height fx fy cx cy [k1 k2 p1 p2 k3 k4 k5 k6]` (OpenCV's rational
// model, up to 8 coefficients); '#' starts a comment.
#pragma once

#include "synth/sensor_model.hpp"

#include <array>
#include <string>
#include <vector>

namespace vobench::synth {

struct CameraSpec {
    PinholeCamera color;
    // Kinect v1 only: the registered depth grid is the colour image divided by this (PUTK² recorded
    // 320×240 depth beside 640×480 colour; TUM recorded depth at the full 640×480).
    int depth_divisor = 1;
    // Kinect v1 only: the depth camera's disparity distortion as the renderer applies it
    // (SensorModel::disparity_distortion_px; zero where none was measured) — chosen so that renderings
    // fitted by `synth fit-distortion` read back `disparity_distortion_fit_px`.
    std::array<double, 3> disparity_distortion_px{};
    // What `synth fit-distortion` measures on the camera's real frames (a, b, c px): the field as that fit
    // sees it, the IR camera's rolling shutter in its row term. `synth undo-distortion` undoes this one.
    std::array<double, 3> disparity_distortion_fit_px{};
    // The turn between the frame the camera's real reference describes and its optical frame, as the
    // renderer applies it (effect reference_frame_error; a rotation vector in camera axes, degrees; zero
    // where none was measured) — chosen so that renderings fitted by `synth fit-distortion --fit-latency
    // --fit-turn` read back what the camera's real frames give.
    std::array<double, 3> reference_turn_deg{};
    // Where the camera's real frames were recorded, as far as the office around a trajectory should
    // follow it: the room is at least this wide and long, metres (0: OfficeOptions' default).
    double min_room_m = 0;
};

std::vector<std::string> camera_names();

// Throws std::invalid_argument naming the name or file (and the line) when it cannot be used.
CameraSpec camera_by_name_or_file(const std::string& name_or_file);

// The sensor seen through another colour camera: Kinect v1's registered depth grid follows the colour
// camera (its size divided by `depth_divisor`); Kinect v2 keeps its own depth camera.
SensorModel with_color_camera(SensorModel sensor, const CameraSpec& camera);

}  // namespace vobench::synth
