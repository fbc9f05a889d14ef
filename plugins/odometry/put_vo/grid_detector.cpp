#include "grid_detector.hpp"

#include <algorithm>

namespace put_vo {

GridDetector::GridDetector(const GridDetectorOptions& o) : options_(o) {
    const int cells = o.grid * o.grid;
    thresholds_.assign(static_cast<std::size_t>(cells), o.threshold_init);
    for (int i = 0; i < cells; ++i)
        // One pyramid level: tracking, not matching, follows; FAST with Harris ranking as ORB does.
        orbs_.push_back(cv::ORB::create(2 * o.per_cell_target, 1.2f, 1, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, o.threshold_init));
}

std::vector<cv::KeyPoint> GridDetector::detect(const cv::Mat& gray) {
    std::vector<cv::KeyPoint> all;
    const int g = options_.grid;
    for (int row = 0; row < g; ++row) {
        for (int col = 0; col < g; ++col) {
            const int cell = row * g + col;
            const int x0 = std::max(0, col * gray.cols / g - options_.overlap_px);
            const int x1 = std::min(gray.cols, (col + 1) * gray.cols / g + options_.overlap_px);
            const int y0 = std::max(0, row * gray.rows / g - options_.overlap_px);
            const int y1 = std::min(gray.rows, (row + 1) * gray.rows / g + options_.overlap_px);
            orbs_[static_cast<std::size_t>(cell)]->setFastThreshold(thresholds_[static_cast<std::size_t>(cell)]);
            std::vector<cv::KeyPoint> kps;
            orbs_[static_cast<std::size_t>(cell)]->detect(gray(cv::Rect(x0, y0, x1 - x0, y1 - y0)), kps);
            // Adapt the threshold for the next key frame: too few → lower it, plenty → raise it.
            int& t = thresholds_[static_cast<std::size_t>(cell)];
            if (static_cast<int>(kps.size()) < options_.per_cell_target)
                t = std::max(options_.threshold_min, t - 3);
            else if (static_cast<int>(kps.size()) >= 2 * options_.per_cell_target)
                t = std::min(options_.threshold_max, t + 3);
            for (cv::KeyPoint& k : kps) {
                k.pt.x += static_cast<float>(x0);
                k.pt.y += static_cast<float>(y0);
                k.class_id = cell;
                all.push_back(k);
            }
        }
    }
    return all;
}

}  // namespace put_vo
