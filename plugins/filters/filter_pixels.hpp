// filter_pixels.hpp — what the built-in filters share: depth in metres from either depth format and
// back, and a seeded generator. Header-only; the filters link only the SDK.
#pragma once

#include <vobench/plugin.hpp>

#include <cmath>
#include <cstdint>
#include <random>

namespace vobench::filters {

// Depth at pixel i (row-packed, as sdk::FrameBuffer keeps it) in metres; 0 when there is no reading.
inline double depth_m(const vobench_frame& f, uint8_t* depth, std::size_t i) {
    if (f.depth->format == VOBENCH_PIXEL_DEPTH_U16) return reinterpret_cast<uint16_t*>(depth)[i] * f.depth_scale;
    const float v = reinterpret_cast<float*>(depth)[i];
    return std::isfinite(v) && v > 0 ? v * f.depth_scale : 0.0;
}

// Writes `metres` (0: no reading) at pixel i, in the frame's unit and format (u16 rounded, clamped).
inline void set_depth_m(const vobench_frame& f, uint8_t* depth, std::size_t i, double metres) {
    const double units = metres > 0 && std::isfinite(metres) ? metres / f.depth_scale : 0.0;
    if (f.depth->format == VOBENCH_PIXEL_DEPTH_U16)
        reinterpret_cast<uint16_t*>(depth)[i] = static_cast<uint16_t>(std::lround(std::min(units, 65535.0)));
    else
        reinterpret_cast<float*>(depth)[i] = static_cast<float>(units);
}

inline std::size_t pixels(const vobench_frame& f) {
    return static_cast<std::size_t>(f.depth->width) * static_cast<std::size_t>(f.depth->height);
}

// Per frame: the same seed and frame index give the same draws, whatever came before (so a dropped or
// resumed frame does not shift the noise of the next ones).
inline std::mt19937_64 frame_rng(uint64_t seed, uint64_t index) {
    std::seed_seq seq{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32), static_cast<uint32_t>(index),
                      static_cast<uint32_t>(index >> 32)};
    return std::mt19937_64(seq);
}

}  // namespace vobench::filters
