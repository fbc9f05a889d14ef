// trajectory_families.hpp — built-in robot paths like PUTK²'s (Kraft et al. 2016, Table 4): four
// exploration paths (long straight sections, sudden turns, loops, driving backwards; 18–40 m) and one
// path driven at four speeds (≈0.16, 0.38, 0.75, 1.04 m/s), sampled at 10 Hz.
//
// They are marker trajectories in the PUTK² world frame (z down, floor at z = 3 m, marker 0.8 m above
// it), so cameras follow them through their camera-in-marker poses exactly as in the real data (eq. 10).
#pragma once

#include "metrics/pose.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace vobench::synth {

constexpr double kFrameRateHz = 10.0;
constexpr double kMarkerZ = 2.2;  // metres below the ceiling cameras

// Names: explore1 … explore4, speed1 … speed4.
std::vector<std::string> trajectory_family_names();
bool is_trajectory_family(const std::string& name);

// The marker trajectory of a family (stamps k / 10 s). Small roll, pitch and height vibrations are
// added deterministically from `seed`. Throws std::invalid_argument for an unknown name.
metrics::Trajectory family_trajectory(const std::string& name, uint64_t seed);

}  // namespace vobench::synth
