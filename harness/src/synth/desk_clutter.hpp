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

// Puts the clutter of a used desk on `desk`, whose upper surface is at z = top.
void furnish_desk(const Box& desk, double top, Random& r, uint64_t& next_seed, const AddBox& add);

}  // namespace vobench::synth
