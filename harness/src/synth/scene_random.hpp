// scene_random.hpp — the office builder's random choices: a counter-based stream (same seed, same
// office) and the materials and colours drawn from it. Shared by office.cpp and desk_clutter.cpp.
#pragma once

#include "synth/random_field.hpp"
#include "synth/texture.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vobench::synth {

class Random {
public:
    explicit Random(uint64_t seed) : state_(seed) {}
    double uniform(double lo, double hi) { return lo + (hi - lo) * synth::uniform(mix64(++state_ * 0x2545f4914f6cdd1dull)); }
    int pick(int n) { return std::min(n - 1, static_cast<int>(uniform(0, n))); }

private:
    uint64_t state_;
};

inline Material material(Random& r, TextureStyle style, Eigen::Vector3f base, Eigen::Vector3f accent, uint64_t seed) {
    Material m;
    m.style = style;
    m.base = base;
    m.accent = accent;
    m.scale = static_cast<float>(r.uniform(0.8, 1.25));
    m.seed = seed;
    return m;
}

inline Eigen::Vector3f colour(Random& r, float lo, float hi) {
    return {static_cast<float>(r.uniform(lo, hi)), static_cast<float>(r.uniform(lo, hi)), static_cast<float>(r.uniform(lo, hi))};
}

// The colour of a manufactured object: a hue times a luminance drawn log-uniformly over 0.03–0.9, so
// that black, mid and white things are equally common, as real surfaces' reflectances spread over
// decades (Attewell & Baddeley 2007) — not all mid-grey pastels.
inline Eigen::Vector3f object_colour(Random& r) {
    Eigen::Vector3f hue = colour(r, 0.15f, 1.0f);
    hue /= hue.maxCoeff();
    return hue * static_cast<float>(std::exp(r.uniform(std::log(0.03), std::log(0.9))));
}

}  // namespace vobench::synth
