// smooth_field.hpp — a smooth Gaussian random field over an image: independent standard normal values
// on a lattice of `spacing` pixels, interpolated with cubic B-spline weights. Every point's weights are
// normalised so that the field has unit variance everywhere (a plain spline of i.i.d. values is less
// variable between the lattice points than on them). Neighbouring pixels are correlated over about
// one lattice spacing. Deterministic: the lattice values are hashes of (seed, index).
#pragma once

#include "synth/random_field.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace vobench::synth {

class SmoothField {
public:
    SmoothField(int width_px, int height_px, double spacing_px, uint64_t seed)
        : spacing_(spacing_px),
          columns_(static_cast<int>(std::ceil(width_px / spacing_px)) + 4),
          rows_(static_cast<int>(std::ceil(height_px / spacing_px)) + 4),
          values_(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_)),
          pixel_columns_(static_cast<std::size_t>(std::max(0, width_px))) {
        for (std::size_t i = 0; i < values_.size(); ++i) values_[i] = gaussian(hash(seed, i));
        for (std::size_t x = 0; x < pixel_columns_.size(); ++x)
            pixel_columns_[x].first = weights(static_cast<double>(x) / spacing_, pixel_columns_[x].w);
    }

    // At pixel position (x, y), 0 <= x < width_px, 0 <= y < height_px.
    double at(double x, double y) const {
        double wx[4], wy[4];
        const int ix = weights(x / spacing_, wx), iy = weights(y / spacing_, wy);
        return combine(ix, wx, iy, wy);
    }

    // The field along row y at the integer pixels x = 0 … width_px − 1, into out: the same values as
    // at(x, y), bit for bit, with the columns' weights computed once per field instead of per pixel
    // (per pixel, this field cost 4.5 % of a tum-fr1 frame; docs/synthetic-sensors.md).
    void row(int y, double* out) const {
        double wy[4];
        const int iy = weights(y / spacing_, wy);
        for (std::size_t x = 0; x < pixel_columns_.size(); ++x) out[x] = combine(pixel_columns_[x].first, pixel_columns_[x].w, iy, wy);
    }

private:
    struct ColumnWeights {
        int first = 0;
        double w[4] = {};
    };

    // The 4×4 lattice values from (ix, iy) on, weighted by wx along the rows and wy across them.
    double combine(int ix, const double wx[4], int iy, const double wy[4]) const {
        double sum = 0;
        for (int j = 0; j < 4; ++j) {
            const double* row =
                &values_[static_cast<std::size_t>(iy + j) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(ix)];
            sum += wy[j] * (wx[0] * row[0] + wx[1] * row[1] + wx[2] * row[2] + wx[3] * row[3]);
        }
        return sum;
    }

    // Cubic B-spline weights of the four lattice points around s, scaled to unit sum of squares; returns
    // the first point's index (the lattice starts one spacing before the image).
    static int weights(double s, double w[4]) {
        const double f = std::floor(s), t = s - f;
        w[0] = (1 - t) * (1 - t) * (1 - t) / 6;
        w[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
        w[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
        w[3] = t * t * t / 6;
        const double norm = 1.0 / std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] + w[3] * w[3]);
        for (int k = 0; k < 4; ++k) w[k] *= norm;
        return static_cast<int>(f);
    }

    double spacing_;
    int columns_, rows_;
    std::vector<double> values_;
    std::vector<ColumnWeights> pixel_columns_;  // weights() of each integer pixel column
};

}  // namespace vobench::synth
