// grid_detector.hpp — ORB key points in a 4×4 grid of slightly overlapping sub-images, each with its
// own FAST threshold adapted frame to frame so that every cell yields a similar number of features
// (Kraft et al. 2016, §5.1: even spatial coverage for a well-conditioned motion estimate).
//
// Two ways to find the corners of a cell: ORB's detector (the paper's), or the same selection
// without what tracking does not use — FAST corners ranked by their Harris score as ORB ranks them,
// but without ORB's orientation and its 31-px descriptor border, so cells need not overlap and
// every pixel is searched once (half the detection time on 640×480 frames).
#pragma once

#include <opencv2/features2d.hpp>

#include <vector>

namespace put_vo {

enum class CornerKind { orb, fast_harris };

struct GridDetectorOptions {
    CornerKind kind = CornerKind::orb;
    int grid = 4;              // cells per side
    int overlap_px = 32;       // orb: ORB ignores ~31 px inside each window's border: overlap by more
    int border_px = 16;        // fast_harris: no corner closer than this to the image's edge (at least 4)
    int per_cell_target = 40;  // features wanted per cell
    int threshold_init = 20, threshold_min = 5, threshold_max = 80;
};

class GridDetector {
public:
    explicit GridDetector(const GridDetectorOptions& options = {});
    // Key points of the whole image, in full-image coordinates. fast_harris ranks by the Harris
    // response of `derivatives` (the image's Scharr derivatives, CV_16SC2, as
    // cv::buildOpticalFlowPyramid gives them for its base level; empty: computed here).
    std::vector<cv::KeyPoint> detect(const cv::Mat& gray, const cv::Mat& derivatives = {});

private:
    std::vector<cv::KeyPoint> detect_cell_orb(const cv::Mat& gray, int cell, cv::Rect window);
    std::vector<cv::KeyPoint> detect_cell_fast_harris(const cv::Mat& gray, int cell, cv::Rect area);
    void adapt_threshold(int cell, std::size_t found);

    GridDetectorOptions options_;
    std::vector<int> thresholds_;  // per cell, carried between calls
    std::vector<cv::Ptr<cv::ORB>> orbs_;
    cv::Mat derivatives_;  // fast_harris: the searched image's Scharr derivatives (given, or computed here)
};

// The Harris & Stephens (1988) corner response det(M) − k·trace(M)² at pixel (x, y), M the sum over
// a block×block window of the gradients' outer products, k = 0.04 (ORB's HARRIS_K); `derivatives`
// holds the image's 3×3 Scharr derivatives (CV_16SC2: x, y), which the LK pyramid already has, in
// place of the Sobel derivatives ORB takes (Scharr's are the more rotation-invariant, and free
// here). Only its order matters, so it is left unnormalised. (x, y) must lie block/2 px inside.
double harris_response(const cv::Mat& derivatives, int x, int y, int block = 7);

// The 3×3 Scharr derivatives of an 8-bit image, CV_16SC2 (x, y), as cv::buildOpticalFlowPyramid's.
cv::Mat scharr_derivatives(const cv::Mat& gray);

}  // namespace put_vo
