// office.hpp — the synthetic office a trajectory is rendered in, built from a seed around the camera
// poses: a room of an office's size with posters, windows and ceiling lights, desks where the cameras
// look down (with their clutter, desk_clutter.hpp), furniture along the walls and in the open, never
// closer than `clearance` to the path, so that the sensor always sees structure within its
// 0.5–4.5 m range, as the PUTK² recording room was arranged. Every surface is a face of an
// axis-aligned box (scene.hpp); the frame is the office frame (z down, floor at z = floor_z).
#pragma once

#include "synth/scene.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace vobench::synth {

struct OfficeOptions {
    uint64_t seed = 1;
    double floor_z = 3.0;    // ceiling cameras 3 m above the floor
    double clearance = 0.7;  // free radius around the path, metres
    double margin = 1.1;     // mean distance from the path's bounding box to the walls, metres
    double min_room = 6.0;   // the room is at least this wide and long, metres (a real office's size)
};

// `camera_poses`: the camera-to-world poses the sensors will take. Where a camera looks down (hand-held
// over a desk, as in TUM's sequences), a desk with clutter is placed where its view meets desk height:
// people point cameras at things. After walls and furniture, every
// 5th pose is checked by casting a coarse fan of rays over the central field of view; where less than
// half of them meet something within 0.5–4.3 m, a textured cabinet is added ahead (beside the path,
// never within `clearance` of it), so the depth sensor always has structure in range.
// The same poses and options give the same office, box for box.
Scene build_office(const std::vector<Eigen::Isometry3d>& camera_poses, const OfficeOptions& options);

}  // namespace vobench::synth
