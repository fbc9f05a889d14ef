#include "synth/texture.hpp"

#include "synth/random_field.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace vobench::synth {
namespace {

// How much of a feature survives, from how many footprints half its size spans: 1 when well
// resolved, 0 below Nyquist.
float resolved_share(double half_size_in_footprints) { return static_cast<float>(std::clamp(half_size_in_footprints - 0.5, 0.0, 1.0)); }

// How much of a feature of size `size` survives a footprint.
float visibility(double size, double footprint) { return resolved_share(size / (2.0 * footprint)); }

// The corner values of the lattice cells a thread drew last, one slot per octave seed (mod 64): the
// pixels of a row mostly fall in the cells their neighbours fell in (at a 1 mm footprint, the octaves'
// cells are 9 mm to 60 cm wide), and a cell's corners depend on (seed, ix, iy) alone, so a hit gives
// the very numbers that hashing them again would (Kinect v2: 2.5 % fewer instructions a frame).
class CellCache {
public:
    double noise(double x, double y, uint64_t seed) {
        const double fx = std::floor(x), fy = std::floor(y);
        const int64_t ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
        Slot& s = slots_[seed & (kSlots - 1)];
        if (!s.filled || s.seed != seed || s.ix != ix || s.iy != iy) s = {true, seed, ix, iy, lattice_cell(ix, iy, seed)};
        return lattice_interpolate(s.cell, x - fx, y - fy);
    }

private:
    static constexpr std::size_t kSlots = 64;
    struct Slot {
        bool filled = false;
        uint64_t seed = 0;
        int64_t ix = 0, iy = 0;
        LatticeCell cell{};
    };
    std::array<Slot, kSlots> slots_{};
};

// Fractal noise whose octaves are dropped as they fall below the footprint.
// Octave k has the size base_size·2⁻ᵏ. Scaling by a power of two commutes with rounding, so the
// lattice coordinates u / size = 2ᵏ·(u / base_size) and the resolution size / (2·footprint) =
// 2⁻ᵏ·(base_size / (2·footprint)) are exactly what dividing in every octave gives: the divisions are
// done once.
double fbm(double u, double v, double base_size, int octaves, double footprint, uint64_t seed) {
    thread_local CellCache cells;
    double sum = 0, amp = 1, norm = 0;
    double x = u / base_size, y = v / base_size, resolved = base_size / (2.0 * footprint);
    for (int k = 0; k < octaves; ++k) {
        const float vis = resolved_share(resolved);  // visibility(size, footprint)
        if (vis <= 0) break;
        sum += amp * vis * cells.noise(x, y, seed + k);
        norm += amp;
        amp *= 0.55;
        x *= 2.0;
        y *= 2.0;
        resolved *= 0.5;
    }
    return norm > 0 ? sum / norm : 0.0;
}

Eigen::Vector3f mix(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float t) { return a + (b - a) * t; }

// A dark line of width w on a grid of pitch p, faded by the footprint.
float grid_line(double x, double pitch, double width, double footprint) {
    const double d = std::abs(x / pitch - std::round(x / pitch)) * pitch;
    const float vis = visibility(width, footprint);
    return d < width * 0.5 ? vis : 0.0f;
}

Eigen::Vector3f pages(const Material& m, double u, double v, double footprint) {
    // Printed pages: rows of word-like marks, 2 cm line pitch, inside 21×30 cm sheets.
    const double su = std::fmod(std::abs(u), 0.25), sv = std::fmod(std::abs(v), 0.34);
    if (su > 0.21 || sv > 0.30) return m.accent;
    const double row = std::floor(sv / 0.02);
    const double in_row = sv - row * 0.02;
    const float vis = visibility(0.008, footprint);
    if (in_row > 0.009 || vis <= 0) return mix(m.base, m.base * 0.8f, 1.0f - vis);
    const double word = std::floor(su / 0.035);
    const double in_word = su - word * 0.035;
    const double length = 0.01 + 0.022 * uniform(hash(m.seed, static_cast<uint64_t>(row), static_cast<uint64_t>(word + 1e4)));
    const bool ink = in_word < length;
    return ink ? mix(m.base * 0.8f, Eigen::Vector3f(0.08f, 0.08f, 0.1f), vis) : mix(m.base, m.base * 0.8f, 1.0f - vis);
}

// The last pattern cell a thread looked up, one slot per kind of cell: a cell of the marks and
// posters is 12 cm wide, a tile 50 cm, a key 1.9 cm — many pixels of a row each — and its values
// depend on (seed, cu, cv) alone, so a hit gives the very values its hashing would.
template <typename Cell, Cell (*make)(uint64_t, int64_t, int64_t)>
const Cell& cached_cell(uint64_t seed, int64_t cu, int64_t cv) {
    struct Slot {
        bool filled = false;
        uint64_t seed = 0;
        int64_t cu = 0, cv = 0;
        Cell cell{};
    };
    thread_local Slot slot;
    if (!slot.filled || slot.seed != seed || slot.cu != cu || slot.cv != cv) slot = {true, seed, cu, cv, make(seed, cu, cv)};
    return slot.cell;
}

// The hash key of the cell holding x (in cells) for the tiles and keys: floor(x) + 10⁵, as an
// unsigned integer (kept in an int64_t's bits for cached_cell).
int64_t lattice_key(double x) { return static_cast<int64_t>(static_cast<uint64_t>(std::floor(x) + 1e5)); }

// A tile's own shade, and whether a key carries a legend.
struct TileCell {
    float shade = 1;
};
TileCell tile_cell(uint64_t seed, int64_t a, int64_t b) {
    return {0.85f + 0.3f * static_cast<float>(uniform(hash(seed, static_cast<uint64_t>(a), static_cast<uint64_t>(b))))};
}
struct KeyCell {
    bool labelled = false;
};
KeyCell key_cell(uint64_t seed, int64_t a, int64_t b) {
    return {uniform(hash(seed, static_cast<uint64_t>(a), static_cast<uint64_t>(b))) < 0.8};
}

// A poster cell: its colour and which of three shapes it holds.
struct PosterCell {
    Eigen::Vector3f colour{0, 0, 0};
    uint64_t shape = 0;
};

PosterCell poster_cell(uint64_t seed, int64_t cu, int64_t cv) {
    const uint64_t h = hash(seed, static_cast<uint64_t>(cu), static_cast<uint64_t>(cv));
    return {
        Eigen::Vector3f(static_cast<float>(uniform(h)), static_cast<float>(uniform(mix64(h))), static_cast<float>(uniform(mix64(h + 1)))),
        h % 3};
}

Eigen::Vector3f poster(const Material& m, double u, double v, double footprint) {
    // Cells of 12 cm, each with a coloured disc or bar on a light ground; large shapes, sharp corners.
    const double cell = 0.12 * m.scale;
    const int64_t cu = static_cast<int64_t>(std::floor(u / cell)), cv = static_cast<int64_t>(std::floor(v / cell));
    const PosterCell& c = cached_cell<PosterCell, poster_cell>(m.seed, cu, cv);
    const double lu = u / cell - static_cast<double>(cu) - 0.5, lv = v / cell - static_cast<double>(cv) - 0.5;
    const float vis = visibility(cell * 0.5, footprint);
    bool inside;
    switch (c.shape) {
        case 0: inside = lu * lu + lv * lv < 0.12; break;
        case 1: inside = std::abs(lu) < 0.4 && std::abs(lv) < 0.15; break;
        default: inside = std::abs(lu) < 0.2 && std::abs(lv) < 0.35; break;
    }
    const Eigen::Vector3f ground = m.base;
    const Eigen::Vector3f mean = 0.75f * ground + 0.25f * c.colour;
    return mix(mean, inside ? c.colour : ground, vis);
}

// Small rectangles (2–7 cm) scattered on a 12 cm lattice, 65 % of the cells occupied; dark or light.
constexpr double kMarkCell = 0.12;

// A cell's mark: its size, its offset in the cell and its shade (none in an empty cell).
struct MarkCell {
    bool occupied = false;
    double w = 0, hgt = 0, ou = 0, ov = 0;
    float shade = 1;
};

MarkCell mark_cell(uint64_t seed, int64_t cu, int64_t cv) {
    const uint64_t h = hash(seed ^ 0x5bd1e995ull, static_cast<uint64_t>(cu), static_cast<uint64_t>(cv));
    MarkCell c;
    if (uniform(h) < 0.35) return c;
    c.occupied = true;
    c.w = 0.02 + 0.05 * uniform(mix64(h + 1));
    c.hgt = 0.02 + 0.05 * uniform(mix64(h + 2));
    c.ou = (kMarkCell - c.w) * uniform(mix64(h + 3));
    c.ov = (kMarkCell - c.hgt) * uniform(mix64(h + 4));
    c.shade = uniform(mix64(h + 5)) < 0.6 ? 0.25f : 1.6f;
    return c;
}

Eigen::Vector3f marks(const Material& m, double u, double v, double footprint, const Eigen::Vector3f& ground) {
    const double cell = kMarkCell;
    const int64_t cu = static_cast<int64_t>(std::floor(u / cell)), cv = static_cast<int64_t>(std::floor(v / cell));
    const MarkCell& c = cached_cell<MarkCell, mark_cell>(m.seed, cu, cv);
    if (!c.occupied) return ground;
    const double lu = u - static_cast<double>(cu) * cell - c.ou, lv = v - static_cast<double>(cv) * cell - c.ov;
    const float vis = visibility(std::min(c.w, c.hgt), footprint);
    const Eigen::Vector3f mark = (ground * c.shade).cwiseMin(Eigen::Vector3f::Ones());
    const float area = static_cast<float>(c.w * c.hgt / (cell * cell));
    const Eigen::Vector3f mean = ground + (mark - ground) * area;  // what a blurred view averages to
    const bool inside = lu >= 0 && lu < c.w && lv >= 0 && lv < c.hgt;
    return mix(mean, inside ? mark : ground, vis);
}

// A photo-like print: three octave bands of colour noise with 1/f amplitude, quantised into regions
// with hard edges (objects in a photo), over a light ground.
Eigen::Vector3f photo(const Material& m, double u, double v, double footprint) {
    const double s = 0.25 * m.scale;
    const double a = fbm(u, v, s, 7, footprint, m.seed), b = fbm(u, v, s, 7, footprint, m.seed + 31),
                 c = fbm(u, v, 0.5 * s, 6, footprint, m.seed + 57);
    const float vis = visibility(0.02, footprint);
    // Regions: the sign pattern of a coarse field gives object-like patches with sharp boundaries.
    const double region = fbm(u, v, 0.6 * s, 4, footprint, m.seed + 91);
    const float edge = region > 0.05 ? 1.0f : region < -0.05 ? 0.0f : static_cast<float>((region + 0.05) / 0.1);
    const float hard = vis * edge + (1 - vis) * 0.5f;
    const Eigen::Vector3f field(static_cast<float>(0.5 + 0.9 * a), static_cast<float>(0.5 + 0.9 * b), static_cast<float>(0.5 + 0.9 * c));
    const Eigen::Vector3f light = m.base.cwiseProduct(field.cwiseMax(0.05f).cwiseMin(1.4f));
    const Eigen::Vector3f dark = m.accent.cwiseProduct(field.cwiseMax(0.05f).cwiseMin(1.4f)) * 0.6f;
    return mix(dark, light, hard).cwiseMin(Eigen::Vector3f::Ones());
}

// Keys of 1.9 cm pitch with 0.3 cm gaps, a pale legend mark on some; the frame around is the base.
Eigen::Vector3f keys(const Material& m, double u, double v, double footprint) {
    const double pitch = 0.019;
    const double fu = u / pitch - std::floor(u / pitch), fv = v / pitch - std::floor(v / pitch);
    const float vis = visibility(0.004, footprint);
    const bool gap = fu < 0.16 || fv < 0.16;
    const bool labelled = cached_cell<KeyCell, key_cell>(m.seed, lattice_key(u / pitch), lattice_key(v / pitch)).labelled;
    const bool legend = !gap && std::abs(fu - 0.55) < 0.12 && std::abs(fv - 0.5) < 0.16 && labelled;
    const Eigen::Vector3f key = legend ? m.accent : m.base;
    const Eigen::Vector3f mean = 0.75f * m.base + 0.2f * m.base * 0.4f + 0.05f * m.accent;
    return mix(mean, gap ? m.base * 0.4f : key, vis);
}

}  // namespace

Eigen::Vector3f albedo(const Material& m, double u, double v, double footprint) {
    switch (m.style) {
        case TextureStyle::Paint: {
            // Mottled paint with labels, switches, scuffs and screw heads: real walls and furniture carry
            // small high-contrast marks, which is where FAST finds its corners.
            const double n = fbm(u, v, 0.6 * m.scale, 7, footprint, m.seed);
            const Eigen::Vector3f paint = m.base * static_cast<float>(1.0 + 0.6 * n);
            return marks(m, u, v, footprint, paint);
        }
        case TextureStyle::Tiles: {
            const double n = fbm(u, v, 0.3 * m.scale, 5, footprint, m.seed);
            const float line = std::max(grid_line(u, 0.5 * m.scale, 0.012, footprint), grid_line(v, 0.5 * m.scale, 0.012, footprint));
            // Each tile its own shade: corners where four tiles meet.
            const float shade =
                cached_cell<TileCell, tile_cell>(m.seed, lattice_key(u / (0.5 * m.scale)), lattice_key(v / (0.5 * m.scale))).shade;
            return mix(m.base * shade * static_cast<float>(1.0 + 0.25 * n), m.accent, line);
        }
        case TextureStyle::Wood: {
            const double n = fbm(u * 0.15, v, 0.08 * m.scale, 5, footprint, m.seed);
            const double grain = 0.5 + 0.5 * std::sin((v + 0.05 * n) / (0.012 * m.scale));
            const float vis = visibility(0.012 * m.scale, footprint);
            const float plank = grid_line(v, 0.15 * m.scale, 0.004, footprint);
            return mix(mix(m.base, m.accent, static_cast<float>(0.35 * grain * vis + 0.175 * (1 - vis))), m.accent * 0.5f, plank);
        }
        case TextureStyle::Pages: return pages(m, u, v, footprint);
        case TextureStyle::Poster: return poster(m, u, v, footprint);
        case TextureStyle::Photo: return photo(m, u, v, footprint);
        case TextureStyle::Keys: return keys(m, u, v, footprint);
        case TextureStyle::Screen: {
            // Nearly black with faint smudges; what it shows is mostly the specular highlight.
            const double n = fbm(u, v, 0.1, 3, footprint, m.seed);
            return m.base * static_cast<float>(1.0 + 0.3 * n);
        }
        case TextureStyle::Fabric: {
            const float vis = visibility(0.004, footprint);
            const double weave = 0.5 + 0.25 * (std::sin(u / 0.0015) * std::sin(v / 0.0015));
            const double n = fbm(u, v, 0.15, 4, footprint, m.seed);
            return mix(m.base, m.accent, static_cast<float>(std::clamp(vis * weave + (1 - vis) * 0.5 + 0.3 * n, 0.0, 1.0)));
        }
        case TextureStyle::Carpet: {
            const double n = fbm(u, v, 0.05 * m.scale, 4, footprint, m.seed) + 0.5 * fbm(u, v, 0.8, 3, footprint, m.seed + 7);
            return mix(m.base, m.accent, static_cast<float>(std::clamp(0.5 + 0.8 * n, 0.0, 1.0)));
        }
    }
    return m.base;
}

}  // namespace vobench::synth
