// random_field.hpp — counter-based randomness: every random number is a hash of (seed, indices), so a
// value never depends on thread scheduling or evaluation order. Same seed, same bytes.
#pragma once

#include <cmath>
#include <cstdint>

namespace vobench::synth {

// SplitMix64 finaliser (Steele, Lea & Flood 2014): a strong 64-bit mixer.
inline uint64_t mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

inline uint64_t hash(uint64_t a, uint64_t b) { return mix64(a ^ mix64(b)); }
inline uint64_t hash(uint64_t a, uint64_t b, uint64_t c) { return hash(hash(a, b), c); }
inline uint64_t hash(uint64_t a, uint64_t b, uint64_t c, uint64_t d) { return hash(hash(a, b, c), d); }

// hash(a, b, c, ·) with its first three arguments mixed once: the per-pixel stream of one effect in
// one frame, hash(a, b, c, d) == HashStream(a, b, c)(d). Two mixing rounds a draw instead of six.
class HashStream {
public:
    HashStream(uint64_t a, uint64_t b, uint64_t c) : prefix_(hash(a, b, c)) {}
    uint64_t operator()(uint64_t d) const { return hash(prefix_, d); }

private:
    uint64_t prefix_;
};

// Uniform in [0, 1).
inline double uniform(uint64_t h) { return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0); }

// Standard normal from one hash (Box–Muller on two halves of the stream).
inline double gaussian(uint64_t h) {
    const double u1 = uniform(mix64(h)) + 1e-300;
    const double u2 = uniform(mix64(h + 0x632be59bd9b4e019ull));
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

// Approximately standard normal, cheap: the Irwin–Hall sum of four 16-bit uniforms from one hash,
// centred and scaled to unit variance (tails end at ±3.46σ). For image noise, where millions are drawn.
inline double gaussian_fast(uint64_t h) {
    h = mix64(h);
    const double sum = static_cast<double>((h & 0xffff) + ((h >> 16) & 0xffff) + ((h >> 32) & 0xffff) + (h >> 48));
    return (sum / 65536.0 - 2.0) * 1.7320508075688772;  // variance of the sum of 4 U(0,1) is 1/3
}

// Value noise on the integer lattice (smoothly interpolated corner values), in [-1, 1]: the building
// block of the textures and of the blobs in which depth returns get lost.
inline double smoothstep01(double t) { return t * t * (3.0 - 2.0 * t); }

// The values at the four corners of lattice cell (ix, iy), in [-1, 1]: one mixing round per corner
// (large odd multipliers keep neighbouring corners apart).
struct LatticeCell {
    double c00, c10, c01, c11;  // at (ix, iy), (ix + 1, iy), (ix, iy + 1), (ix + 1, iy + 1)
};

inline LatticeCell lattice_cell(int64_t ix, int64_t iy, uint64_t seed) {
    auto corner = [&](int64_t a, int64_t b) {
        return 2.0 * uniform(mix64(seed ^ (static_cast<uint64_t>(a) * 0x9e3779b97f4a7c15ull) ^
                                   (static_cast<uint64_t>(b) * 0xc2b2ae3d27d4eb4full))) -
               1.0;
    };
    return {corner(ix, iy), corner(ix + 1, iy), corner(ix, iy + 1), corner(ix + 1, iy + 1)};
}

// The cell's corner values interpolated at the fractions (tx, ty) of the way across it, smoothly.
inline double lattice_interpolate(const LatticeCell& c, double fraction_x, double fraction_y) {
    const double tx = smoothstep01(fraction_x), ty = smoothstep01(fraction_y);
    const double top = c.c00 + tx * (c.c10 - c.c00);
    const double bottom = c.c01 + tx * (c.c11 - c.c01);
    return top + ty * (bottom - top);
}

inline double lattice_noise(double x, double y, uint64_t seed) {
    const double fx = std::floor(x), fy = std::floor(y);
    return lattice_interpolate(lattice_cell(static_cast<int64_t>(fx), static_cast<int64_t>(fy), seed), x - fx, y - fy);
}

}  // namespace vobench::synth
