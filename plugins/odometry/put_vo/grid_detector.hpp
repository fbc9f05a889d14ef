// grid_detector.hpp — ORB key points in a 4×4 grid of slightly overlapping sub-images, each with its
// own FAST threshold adapted frame to frame so that every cell yields a similar number of features
// (Kraft et al. 2016, §5.1: even spatial coverage for a well-conditioned motion estimate).
#pragma once

#include <opencv2/features2d.hpp>

#include <vector>

namespace put_vo {

struct GridDetectorOptions {
    int grid = 4;              // cells per side
    int overlap_px = 32;       // ORB ignores ~31 px inside each window's border: overlap by more
    int per_cell_target = 40;  // features wanted per cell
    int threshold_init = 20, threshold_min = 5, threshold_max = 80;
};

class GridDetector {
public:
    explicit GridDetector(const GridDetectorOptions& options = {});
    // Key points of the whole image, in full-image coordinates.
    std::vector<cv::KeyPoint> detect(const cv::Mat& gray);

private:
    GridDetectorOptions options_;
    std::vector<int> thresholds_;  // per cell, carried between calls
    std::vector<cv::Ptr<cv::ORB>> orbs_;
};

}  // namespace put_vo
