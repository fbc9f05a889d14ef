// dbscan.hpp — DBSCAN (Ester et al. 1996) over key-point positions, keeping the strongest key point
// of each cluster and every unclustered one: dense blobs of corners (text, texture) then give one
// feature each instead of many that LK would confuse (Kraft et al. 2016, §5.1).
#pragma once

#include <opencv2/core.hpp>

#include <vector>

namespace put_vo {

// eps in pixels; min_points counts the point itself. Neighbour search on a hash grid of cell eps.
std::vector<cv::KeyPoint> dbscan_strongest(const std::vector<cv::KeyPoint>& points, double eps, int min_points);

}  // namespace put_vo
