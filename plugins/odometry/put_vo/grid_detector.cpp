#include "grid_detector.hpp"

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace put_vo {

GridDetector::GridDetector(const GridDetectorOptions& o) : options_(o) {
    const int cells = o.grid * o.grid;
    thresholds_.assign(static_cast<std::size_t>(cells), o.threshold_init);
    options_.border_px = std::max(options_.border_px, 4);  // the Harris window and its Scharr taps stay inside
    if (o.kind == CornerKind::orb)
        for (int i = 0; i < cells; ++i)
            // One pyramid level: tracking, not matching, follows; FAST with Harris ranking as ORB does.
            orbs_.push_back(cv::ORB::create(2 * o.per_cell_target, 1.2f, 1, 31, 0, 2, cv::ORB::HARRIS_SCORE, 31, o.threshold_init));
}

std::vector<cv::KeyPoint> GridDetector::detect(const cv::Mat& gray, const cv::Mat& derivatives) {
    std::vector<cv::KeyPoint> all;
    if (options_.kind == CornerKind::fast_harris) {
        // Once for the image: each candidate's Harris window then sums precomputed gradients.
        if (derivatives.empty())
            derivatives_ = scharr_derivatives(gray);
        else if (derivatives.type() != CV_16SC2 || derivatives.size() != gray.size())
            throw std::invalid_argument("GridDetector: the derivatives must be CV_16SC2 and of the image's size");
        else
            derivatives_ = derivatives;
    }
    const int g = options_.grid;
    for (int row = 0; row < g; ++row) {
        for (int col = 0; col < g; ++col) {
            const int cell = row * g + col;
            const int x0 = col * gray.cols / g, x1 = (col + 1) * gray.cols / g;
            const int y0 = row * gray.rows / g, y1 = (row + 1) * gray.rows / g;
            std::vector<cv::KeyPoint> kps;
            if (options_.kind == CornerKind::orb) {
                const int o = options_.overlap_px;
                const int wx0 = std::max(0, x0 - o), wx1 = std::min(gray.cols, x1 + o);
                const int wy0 = std::max(0, y0 - o), wy1 = std::min(gray.rows, y1 + o);
                kps = detect_cell_orb(gray, cell, cv::Rect(wx0, wy0, wx1 - wx0, wy1 - wy0));
            } else {
                const int b = options_.border_px;
                const int ax0 = std::max(x0, b), ax1 = std::min(x1, gray.cols - b);
                const int ay0 = std::max(y0, b), ay1 = std::min(y1, gray.rows - b);
                if (ax1 > ax0 && ay1 > ay0) kps = detect_cell_fast_harris(gray, cell, cv::Rect(ax0, ay0, ax1 - ax0, ay1 - ay0));
            }
            for (cv::KeyPoint& k : kps) {
                k.class_id = cell;
                all.push_back(k);
            }
        }
    }
    return all;
}

std::vector<cv::KeyPoint> GridDetector::detect_cell_orb(const cv::Mat& gray, int cell, cv::Rect window) {
    cv::ORB& orb = *orbs_[static_cast<std::size_t>(cell)];
    orb.setFastThreshold(thresholds_[static_cast<std::size_t>(cell)]);
    std::vector<cv::KeyPoint> kps;
    orb.detect(gray(window), kps);
    adapt_threshold(cell, kps.size());
    for (cv::KeyPoint& k : kps) k.pt += cv::Point2f(static_cast<float>(window.x), static_cast<float>(window.y));
    return kps;
}

// ORB's selection (FAST corners, the 2n strongest by FAST score, of those the n best by Harris score)
// over the cell's own pixels. FAST reads a 3-px circle, so it is given the area grown by 3 px and
// only the corners inside the area are kept.
std::vector<cv::KeyPoint> GridDetector::detect_cell_fast_harris(const cv::Mat& gray, int cell, cv::Rect area) {
    const cv::Rect grown = (area + cv::Size(6, 6) - cv::Point(3, 3)) & cv::Rect(0, 0, gray.cols, gray.rows);
    std::vector<cv::KeyPoint> found;
    cv::FAST(gray(grown), found, thresholds_[static_cast<std::size_t>(cell)], true);
    std::vector<cv::KeyPoint> kps;
    kps.reserve(found.size());
    for (cv::KeyPoint k : found) {
        k.pt += cv::Point2f(static_cast<float>(grown.x), static_cast<float>(grown.y));
        if (area.contains(cv::Point(static_cast<int>(k.pt.x), static_cast<int>(k.pt.y)))) kps.push_back(k);
    }
    const int n = 2 * options_.per_cell_target;  // what ORB is asked for in the other mode
    adapt_threshold(cell, std::min(kps.size(), static_cast<std::size_t>(n)));
    cv::KeyPointsFilter::retainBest(kps, 2 * n);
    for (cv::KeyPoint& k : kps)
        k.response = static_cast<float>(harris_response(derivatives_, static_cast<int>(k.pt.x), static_cast<int>(k.pt.y)));
    cv::KeyPointsFilter::retainBest(kps, n);
    return kps;
}

// Too few corners → a lower threshold for the next key frame; plenty → a higher one.
void GridDetector::adapt_threshold(int cell, std::size_t found) {
    int& t = thresholds_[static_cast<std::size_t>(cell)];
    if (static_cast<int>(found) < options_.per_cell_target)
        t = std::max(options_.threshold_min, t - 3);
    else if (static_cast<int>(found) >= 2 * options_.per_cell_target)
        t = std::min(options_.threshold_max, t + 3);
}

double harris_response(const cv::Mat& derivatives, int x, int y, int block) {
    const int r = block / 2;
    std::int64_t sxx = 0, syy = 0, sxy = 0;
    for (int v = y - r; v <= y + r; ++v) {
        const short* d = derivatives.ptr<short>(v) + 2 * (x - r);
        std::int64_t row_xx = 0, row_yy = 0, row_xy = 0;  // |Scharr| ≤ 16·255: each product fits 32 bits
        for (int u = 0; u < block; ++u) {
            const int dx = d[2 * u], dy = d[2 * u + 1];
            row_xx += dx * dx;
            row_yy += dy * dy;
            row_xy += dx * dy;
        }
        sxx += row_xx;
        syy += row_yy;
        sxy += row_xy;
    }
    const double a = static_cast<double>(sxx), b = static_cast<double>(syy), c = static_cast<double>(sxy);
    return a * b - c * c - 0.04 * (a + b) * (a + b);
}

cv::Mat scharr_derivatives(const cv::Mat& gray) {
    cv::Mat dx, dy, both;
    cv::Scharr(gray, dx, CV_16S, 1, 0);
    cv::Scharr(gray, dy, CV_16S, 0, 1);
    cv::merge(std::vector<cv::Mat>{dx, dy}, both);
    return both;
}

}  // namespace put_vo
