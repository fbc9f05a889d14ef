// reference_frame_error.hpp — a real reference describes a frame a little turned from the camera's
// optical frame (effect `reference_frame_error`).
//
// A motion-capture reference tracks markers on the camera's housing; a hand–eye calibration carries
// their poses to the optical centre, and the camera's own calibration places the optical axis. Both
// err by a fixed rotation, so every relative rotation of the reference is the camera's conjugated by it:
// a rotation Θ over a segment is reported off by about 2·sin(Θ/2)·|X| about an axis turned by Θ — an error
// that grows with the motion, the same in every segment, and that no algorithm can remove.
//
// Measured on TUM's fr1/rpy sample without any algorithm's result: the depth residual under the
// reference's motion at a 16-frame gap (`synth stats --camera tum-fr1`, the depth corrected for its
// disparity distortion) is least with the reference's camera turned by −1.5° about the image's x axis
// (0.651 → 0.618 % of z; −0.75°: 0.624, −2.25°: 0.622, ±1° about y or z: 0.645–1.24). The
// feature-based algorithms' 1-s rotations on the same sample agree (docs/synthetic-sensors.md).
// A rendering's reference is exact unless given one: with the effect, the poses written to
// groundtruth.txt are the rendered camera's turned by that angle about an axis drawn from the seed
// (an unseen sequence's axis is not known; fr1/rpy's is only one draw).
#pragma once

#include "metrics/pose.hpp"

#include <Eigen/Geometry>

#include <cstdint>

namespace vobench::synth {

// The turn of the seed's reference: `angle_rad` about an axis uniform on the sphere (its own hash
// stream, so no other random number of the rendering moves). Identity for an angle of 0.
Eigen::Quaterniond reference_frame_error(uint64_t seed, double angle_rad);

// Every pose's orientation right-multiplied by `turn` (the frame the reference describes, in camera
// coordinates); positions unchanged: the turn is about the optical centre.
void turn_reference_frame(metrics::Trajectory& poses, const Eigen::Quaterniond& turn);

}  // namespace vobench::synth
