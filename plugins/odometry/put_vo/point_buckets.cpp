#include "point_buckets.hpp"

#include <algorithm>
#include <cmath>

namespace put_vo {

namespace {
constexpr double kMaxCellsPerSide = 2048;  // ~4 M cells at most
}

PointBuckets::PointBuckets(const std::vector<cv::Point2f>& points, double cell) : points_(points) {
    bool any = false;
    double x1 = 0, y1 = 0;
    for (const cv::Point2f& p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
        x0_ = any ? std::min(x0_, static_cast<double>(p.x)) : p.x;
        y0_ = any ? std::min(y0_, static_cast<double>(p.y)) : p.y;
        x1 = any ? std::max(x1, static_cast<double>(p.x)) : p.x;
        y1 = any ? std::max(y1, static_cast<double>(p.y)) : p.y;
        any = true;
    }
    if (!any) return;
    cell_x_ = std::max(cell, (x1 - x0_) / kMaxCellsPerSide);
    cell_y_ = std::max(cell, (y1 - y0_) / kMaxCellsPerSide);
    // The grid starts at a multiple of the cell, so the cells are the same whatever the points' box.
    x0_ = std::floor(x0_ / cell_x_) * cell_x_;
    y0_ = std::floor(y0_ / cell_y_) * cell_y_;
    columns_ = static_cast<long>((x1 - x0_) / cell_x_) + 1;
    rows_ = static_cast<long>((y1 - y0_) / cell_y_) + 1;
    // Counting sort by cell, filled in index order; points that are not finite go in no cell.
    const std::size_t none = static_cast<std::size_t>(columns_ * rows_);
    std::vector<std::size_t> cell_of(points.size(), none);
    start_.assign(none + 1, 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const long x = column_of(points[i].x), y = row_of(points[i].y);
        if (x < 0 || y < 0 || x >= columns_ || y >= rows_) continue;
        cell_of[i] = static_cast<std::size_t>(y * columns_ + x);
        ++start_[cell_of[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
    order_.resize(start_.back());
    for (std::size_t i = 0; i < points.size(); ++i)
        if (cell_of[i] != none) order_[next[cell_of[i]]++] = i;
}

// Cells counted from the grid's origin; a query outside the points' box lands in a column or row
// outside the grid (clamped to one past it either way, −2 when not finite, so a far query cannot
// overflow), whose cells are empty.
long PointBuckets::column_of(float x) const {
    return std::isfinite(x) ? static_cast<long>(std::clamp(std::floor((x - x0_) / cell_x_), -2.0, static_cast<double>(columns_ + 1))) : -2;
}
long PointBuckets::row_of(float y) const {
    return std::isfinite(y) ? static_cast<long>(std::clamp(std::floor((y - y0_) / cell_y_), -2.0, static_cast<double>(rows_ + 1))) : -2;
}

}  // namespace put_vo
