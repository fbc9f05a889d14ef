// put_vo's feature selection: the point buckets against a brute-force search, the Harris response
// against OpenCV's dense cv::cornerHarris, and the fast_harris grid detector's cells and border.
#include "dbscan.hpp"         // plugins/odometry/put_vo
#include "grid_detector.hpp"  // plugins/odometry/put_vo
#include "point_buckets.hpp"  // plugins/odometry/put_vo

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <limits>
#include <random>

namespace {

// A texture with corners at many scales: blurred noise plus sharp rectangles (seeded).
cv::Mat textured(int width, int height, unsigned seed) {
    cv::Mat img(height, width, CV_8U);
    cv::RNG rng(seed);
    rng.fill(img, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(img, img, cv::Size(0, 0), 2.0);
    for (int i = 0; i < 150; ++i) {
        const cv::Point a(rng.uniform(0, width), rng.uniform(0, height));
        cv::rectangle(img, a, a + cv::Point(rng.uniform(4, 40), rng.uniform(4, 40)), cv::Scalar(rng.uniform(0, 256)), cv::FILLED);
    }
    return img;
}

}  // namespace

TEST_CASE("PointBuckets: the points within r, as a brute-force search finds them, each cell in index order", "[put_vo][features]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-40.0f, 700.0f);
    std::vector<cv::Point2f> points(2000);
    for (cv::Point2f& p : points) p = {u(rng), u(rng)};
    points[5] = points[6];  // a duplicate
    for (const double cell : {2.0, 5.0, 17.5}) {
        const put_vo::PointBuckets buckets(points, cell);
        for (const double r : {cell, cell / 2}) {
            for (std::size_t i = 0; i < points.size(); i += 7) {
                std::vector<std::size_t> found, expected;
                buckets.for_each_within(points[i], r * r, [&](std::size_t j) { found.push_back(j); });
                for (std::size_t j = 0; j < points.size(); ++j) {
                    const cv::Point2f d = points[j] - points[i];
                    if (d.x * d.x + d.y * d.y <= r * r) expected.push_back(j);
                }
                std::vector<std::size_t> sorted = found;
                std::sort(sorted.begin(), sorted.end());
                REQUIRE(sorted == expected);
            }
        }
    }
    // Points far apart widen the cells (the grid stays small); points that are not finite are never
    // found, and queries far away or not finite find nothing.
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<cv::Point2f> hostile = {{0, 0}, {1, 1}, {1e30f, 5}, {nan, 1}, {inf, 2}, {-1e30f, -1e30f}, {3, 0}};
    const put_vo::PointBuckets far(hostile, 5);
    std::vector<std::size_t> near_origin;
    far.for_each_within({0, 0}, 25, [&](std::size_t j) { near_origin.push_back(j); });
    std::sort(near_origin.begin(), near_origin.end());
    CHECK(near_origin == std::vector<std::size_t>{0, 1, 6});
    std::vector<std::size_t> near_far;
    far.for_each_within({1e30f, 5}, 25, [&](std::size_t j) { near_far.push_back(j); });
    CHECK(near_far == std::vector<std::size_t>{2});
    for (const cv::Point2f q : {cv::Point2f(nan, 0), cv::Point2f(inf, inf), cv::Point2f(3e38f, -3e38f)}) {
        int found = 0;
        far.for_each_within(q, 25, [&](std::size_t) { ++found; });
        CHECK(found == 0);
    }
    const std::vector<cv::Point2f> none;
    int visits = 0;
    put_vo::PointBuckets(none, 5).for_each_within({1, 1}, 25, [&](std::size_t) { ++visits; });
    CHECK(visits == 0);
}

TEST_CASE("harris_response: proportional to cv::cornerHarris (block 7, Scharr, k 0.04) inside the image", "[put_vo][features]") {
    const cv::Mat img = textured(160, 120, 3);
    cv::Mat dense;
    cv::cornerHarris(img, dense, 7, -1, 0.04);  // aperture -1: Scharr's 3×3 derivatives
    const cv::Mat derivatives = put_vo::scharr_derivatives(img);
    // cornerHarris scales Scharr's gradients by s = 1 / (2 · 4 · 7 · 255), so its response is s⁴
    // times the unnormalised one.
    const double s = 1.0 / (2.0 * 4.0 * 7.0 * 255.0), s4 = s * s * s * s;
    double largest = 0;
    for (int y = 4; y < img.rows - 4; ++y)
        for (int x = 4; x < img.cols - 4; ++x) largest = std::max(largest, std::abs(static_cast<double>(dense.at<float>(y, x))));
    REQUIRE(largest > 0);
    int compared = 0;
    for (int y = 4; y < img.rows - 4; y += 3)
        for (int x = 4; x < img.cols - 4; x += 3) {
            // cornerHarris works in float: 0.1 % of the value, or 1e-5 of the image's largest response.
            REQUIRE(put_vo::harris_response(derivatives, x, y) * s4 == Approx(dense.at<float>(y, x)).epsilon(1e-3).margin(1e-5 * largest));
            ++compared;
        }
    CHECK(compared > 1000);
}

TEST_CASE("scharr_derivatives: the LK pyramid's own base-level derivatives", "[put_vo][features]") {
    const cv::Mat img = textured(160, 120, 5);
    std::vector<cv::Mat> pyramid;
    cv::buildOpticalFlowPyramid(img, pyramid, cv::Size(9, 9), 2);
    const cv::Mat mine = put_vo::scharr_derivatives(img);
    REQUIRE(mine.type() == pyramid[1].type());
    REQUIRE(mine.size() == pyramid[1].size());
    // Inside the image (the pyramid's border rule differs from cv::Scharr's at the edge) they agree exactly.
    const cv::Rect inner(1, 1, img.cols - 2, img.rows - 2);
    CHECK(cv::norm(mine(inner), pyramid[1](inner), cv::NORM_INF) == 0);
}

TEST_CASE("GridDetector fast_harris: corners in their own cells, off the border, the strongest kept, deterministic", "[put_vo][features]") {
    const cv::Mat img = textured(640, 480, 11);
    put_vo::GridDetectorOptions o;
    o.kind = put_vo::CornerKind::fast_harris;
    o.per_cell_target = 30;
    o.border_px = 16;
    put_vo::GridDetector detector(o), again(o);
    const std::vector<cv::KeyPoint> kps = detector.detect(img);
    const cv::Mat derivatives = put_vo::scharr_derivatives(img);
    REQUIRE(kps.size() > 16 * 20u);
    std::vector<int> per_cell(16, 0);
    for (const cv::KeyPoint& k : kps) {
        REQUIRE(k.pt.x >= 16);
        REQUIRE(k.pt.y >= 16);
        REQUIRE(k.pt.x < 640 - 16);
        REQUIRE(k.pt.y < 480 - 16);
        const int cell = static_cast<int>(k.pt.y) / 120 * 4 + static_cast<int>(k.pt.x) / 160;
        REQUIRE(k.class_id == cell);  // cells do not overlap: each corner is found once
        ++per_cell[static_cast<std::size_t>(cell)];
        REQUIRE(k.response == Approx(put_vo::harris_response(derivatives, static_cast<int>(k.pt.x), static_cast<int>(k.pt.y))));
    }
    for (int n : per_cell) CHECK(n <= 2 * o.per_cell_target);
    // Given the derivatives (as put_vo gives its pyramid's), the same corners as computing them.
    const std::vector<cv::KeyPoint> repeat = again.detect(img, derivatives);
    REQUIRE(repeat.size() == kps.size());
    for (std::size_t i = 0; i < kps.size(); ++i) REQUIRE(repeat[i].pt == kps[i].pt);
    CHECK_THROWS_AS(again.detect(img, cv::Mat(480, 640, CV_16SC1, cv::Scalar(0))), std::invalid_argument);
    CHECK_THROWS_AS(again.detect(img, derivatives(cv::Rect(0, 0, 320, 240))), std::invalid_argument);
    // With minPts 2 any two corners within ε share a cluster, so the strongest of each cluster and the
    // isolated ones that DBSCAN keeps lie more than ε apart, and fewer remain.
    const std::vector<cv::KeyPoint> clustered = put_vo::dbscan_strongest(kps, 5, 2);
    CHECK(clustered.size() < kps.size());
    for (std::size_t i = 0; i < clustered.size(); ++i)
        for (std::size_t j = i + 1; j < clustered.size(); ++j) REQUIRE(cv::norm(clustered[i].pt - clustered[j].pt) > 5);
    // A blank image has no corners: every cell lowers its threshold for the next frame, none fails.
    CHECK(detector.detect(cv::Mat(480, 640, CV_8U, cv::Scalar(128))).empty());
}
