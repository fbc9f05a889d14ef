// point_buckets.hpp — image points bucketed into a grid of square cells, for "which points lie within
// r of this one" at the cost of the 3×3 cells around it (DBSCAN's ε-neighbourhoods, new features kept
// away from tracked ones). A cell's points come out in increasing index order, so an answer's order
// does not depend on how the buckets were built.
#pragma once

#include <opencv2/core/types.hpp>

#include <cstddef>
#include <vector>

namespace put_vo {

class PointBuckets {
public:
    // `points` must outlive the buckets (points that are not finite are never found); `cell` > 0 is the side of a cell, px, and the
    // largest radius a query may ask for. Points spread so far that the grid would exceed ~4 M cells
    // get wider cells (answers stay exact; only the cost grows).
    PointBuckets(const std::vector<cv::Point2f>& points, double cell);

    // Calls visit(j) for every point j with |points[j] − p|² ≤ r2, cell by cell (3×3 cells around p's,
    // column offset outer, row offset inner), each cell in increasing j.
    template <class Visit>
    void for_each_within(cv::Point2f p, double r2, Visit&& visit) const {
        if (columns_ == 0) return;
        const long cx = column_of(p.x), cy = row_of(p.y);
        for (long dx = -1; dx <= 1; ++dx)
            for (long dy = -1; dy <= 1; ++dy) {
                const long x = cx + dx, y = cy + dy;
                if (x < 0 || y < 0 || x >= columns_ || y >= rows_) continue;
                const std::size_t c = static_cast<std::size_t>(y * columns_ + x);
                for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
                    const std::size_t j = order_[k];
                    const double ddx = p.x - points_[j].x, ddy = p.y - points_[j].y;
                    if (ddx * ddx + ddy * ddy <= r2) visit(j);
                }
            }
    }

private:
    long column_of(float x) const;
    long row_of(float y) const;

    const std::vector<cv::Point2f>& points_;
    double x0_ = 0, y0_ = 0, cell_x_ = 1, cell_y_ = 1;  // the grid's origin and cell sides
    long columns_ = 0, rows_ = 0;
    std::vector<std::size_t> start_;  // cell c's points are order_[start_[c] .. start_[c + 1])
    std::vector<std::size_t> order_;  // point indices by cell, then index
};

}  // namespace put_vo
