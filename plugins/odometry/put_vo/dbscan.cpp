#include "dbscan.hpp"

#include "point_buckets.hpp"

namespace put_vo {

std::vector<cv::KeyPoint> dbscan_strongest(const std::vector<cv::KeyPoint>& points, double eps, int min_points) {
    const std::size_t n = points.size();
    std::vector<cv::Point2f> positions(n);
    for (std::size_t i = 0; i < n; ++i) positions[i] = points[i].pt;
    const PointBuckets buckets(positions, eps);
    const double eps2 = eps * eps;
    auto neighbours = [&](std::size_t i, std::vector<std::size_t>& out) {
        out.clear();
        buckets.for_each_within(positions[i], eps2, [&out](std::size_t j) { out.push_back(j); });
    };
    constexpr int kUnvisited = -2, kNoise = -1;
    std::vector<int> label(n, kUnvisited);
    int clusters = 0;
    std::vector<std::size_t> seeds, found;
    for (std::size_t i = 0; i < n; ++i) {
        if (label[i] != kUnvisited) continue;
        neighbours(i, found);
        if (static_cast<int>(found.size()) < min_points) {
            label[i] = kNoise;
            continue;
        }
        const int c = clusters++;
        label[i] = c;
        seeds = found;
        for (std::size_t k = 0; k < seeds.size(); ++k) {
            const std::size_t j = seeds[k];
            if (label[j] == kNoise) label[j] = c;  // border point
            if (label[j] != kUnvisited) continue;
            label[j] = c;
            neighbours(j, found);
            if (static_cast<int>(found.size()) >= min_points) seeds.insert(seeds.end(), found.begin(), found.end());
        }
    }
    std::vector<int> best(static_cast<std::size_t>(clusters), -1);
    std::vector<cv::KeyPoint> kept;
    for (std::size_t i = 0; i < n; ++i) {
        if (label[i] == kNoise) {
            kept.push_back(points[i]);
            continue;
        }
        int& b = best[static_cast<std::size_t>(label[i])];
        if (b < 0 || points[i].response > points[static_cast<std::size_t>(b)].response) b = static_cast<int>(i);
    }
    for (int b : best) kept.push_back(points[static_cast<std::size_t>(b)]);
    return kept;
}

}  // namespace put_vo
