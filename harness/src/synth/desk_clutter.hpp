// desk_clutter.hpp — office desks and what covers them (monitor, keyboard, papers, books, small
// objects, cables), each thing an axis-aligned box in the office frame (z down).
#pragma once

#include "synth/scene.hpp"
#include "synth/scene_random.hpp"

#include <functional>

namespace vobench::synth {

// Adds a box with its material to the scene being built.
using AddBox = std::function<void(const Eigen::Vector3d& min, const Eigen::Vector3d& max, const Material& m)>;

// A desk top's material: white or grey laminate (most of TUM's desks) or wood.
Material desk_material(Random& r, uint64_t seed);

// A desk as real ones are built, in the footprint of `desk` (its upper surface at z = top, the floor
// at z = floor): a 3-cm top on four legs, open beneath, so that the floor and what stands behind show
// through, as under the desks of TUM's and PUT's rooms; half of them with a modesty panel on one long
// side.
void build_desk(const Box& desk, double top, double floor, Random& r, uint64_t& next_seed, const AddBox& add);

// Puts the clutter of a used desk on `desk`, whose upper surface is at z = top. With `user` (a point in
// the floor plane: where the person working at it stands), the monitor faces the user from the far
// long side; without, from either long side.
void furnish_desk(const Box& desk, double top, Random& r, uint64_t& next_seed, const AddBox& add, const Eigen::Vector2d* user = nullptr);

}  // namespace vobench::synth
