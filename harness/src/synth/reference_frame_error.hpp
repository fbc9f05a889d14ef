// reference_frame_error.hpp — a real reference describes a frame a little turned from the camera's
// optical frame (effect `reference_frame_error`).
//
// A motion-capture reference tracks markers on the camera's housing; a hand–eye calibration carries
// their poses to the optical centre, and the camera's own calibration places the optical axis. Both
// err by a fixed rotation X, so every relative rotation of the reference is the camera's conjugated by
// it: a rotation Θ over a segment is reported off by about 2·sin(Θ/2)·|X| about an axis turned by Θ —
// an error that grows with the motion, the same in every segment, and that no algorithm can remove.
// A rendering's reference is exact unless this effect turns it.
//
// The turn is the camera's (CameraSpec::reference_turn_deg), measured on its real frames' depth and
// reference alone: `vobench synth fit-distortion --fit-latency --fit-turn` fits the disparity field, the
// depth latency and the turn together, and the turn the renderer applies is the one whose renderings
// read back what the real frames give (docs/synthetic-sensors.md, "The reference's frame"). Cameras
// with none measured get none.
#pragma once

#include "metrics/pose.hpp"

#include <Eigen/Geometry>

#include <array>

namespace vobench::synth {

// The rotation of rotation vector `rotation_vector_deg` (camera axes, degrees); identity for zero.
Eigen::Quaterniond reference_turn(const std::array<double, 3>& rotation_vector_deg);

// Every pose's orientation right-multiplied by `turn` (the frame the reference describes, in camera
// coordinates); positions unchanged: the turn is about the optical centre.
void turn_reference_frame(metrics::Trajectory& poses, const Eigen::Quaterniond& turn);

}  // namespace vobench::synth
