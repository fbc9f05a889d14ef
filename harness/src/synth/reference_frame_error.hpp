// reference_frame_error.hpp — a real reference describes a frame a little turned from the camera's
// optical frame (effect `reference_frame_error`).
//
// A motion-capture reference tracks markers on the camera's housing; a hand–eye calibration carries
// their poses to the optical centre, and the camera's own calibration places the optical axis. Both
// err by a fixed rotation, so every relative rotation of the reference is the camera's conjugated by it:
// a rotation Θ over a segment is reported off by about 2·sin(Θ/2)·|X| about an axis turned by Θ — an error
// that grows with the motion, the same in every segment, and that no algorithm can remove.
//
// Off by default, because its size is read off the algorithms' results: on TUM's fr1/rpy sample one
// constant turn of 1.25–1.75° about the image's x axis explains a large share of every image-based
// algorithm's 1-s rotational error (55 % of put_vo's; 1–9 % on exact-reference renderings). The depth
// does not settle it: its residual under the reference's motion at the recorded stamps is least with
// the reference turned 1.5° about x, but at the camera clock's ticks less the measured latency, with
// the disparity field refitted, it is least unturned (docs/synthetic-sensors.md, "The reference's
// frame"). With `+reference_frame_error` the poses written to groundtruth.txt are the rendered
// camera's turned by that angle about an axis drawn from the seed (an unseen sequence's axis is not
// known), so what such an error costs each algorithm can be measured.
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
