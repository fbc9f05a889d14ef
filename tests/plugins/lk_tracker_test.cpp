// put_vo's Lucas–Kanade tracker against the one it stands in for: cv::calcOpticalFlowPyrLK, bit for
// bit, on a texture moved by a known sub-pixel shift and on real fr1/rpy frames.
#include "lk_tracker.hpp"  // plugins/odometry/put_vo
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace {

struct Tracks {
    std::vector<cv::Point2f> to;
    std::vector<unsigned char> status;
};

std::vector<cv::Mat> pyramid(const cv::Mat& gray, cv::Size window, int levels) {
    std::vector<cv::Mat> p;
    const int border = put_vo::lk_pyramid_border(window);
    cv::buildOpticalFlowPyramid(gray, p, cv::Size(border, border), levels);
    return p;
}

Tracks with_opencv(const std::vector<cv::Mat>& a, const std::vector<cv::Mat>& b, const std::vector<cv::Point2f>& from,
                   const std::vector<cv::Point2f>& start, const put_vo::LkOptions& o) {
    Tracks t{start, {}};
    std::vector<float> error;  // asked for, as put_vo asked: OpenCV then also drops tracks ending out of reach
    cv::calcOpticalFlowPyrLK(a, b, from, t.to, t.status, error, o.window, o.levels,
                             cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, o.max_iterations, o.epsilon),
                             o.use_initial_flow ? cv::OPTFLOW_USE_INITIAL_FLOW : 0);
    return t;
}

Tracks with_own(const std::vector<cv::Mat>& a, const std::vector<cv::Mat>& b, const std::vector<cv::Point2f>& from,
                const std::vector<cv::Point2f>& start, const put_vo::LkOptions& o) {
    Tracks t{start, {}};
    put_vo::track_lk(a, b, from, t.to, t.status, o);
    return t;
}

// Bit-identical positions (compared as bytes, so that -0 and NaN count too) and status.
std::size_t differing(const Tracks& x, const Tracks& y) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < x.to.size(); ++i)
        if (x.status[i] != y.status[i] || std::memcmp(&x.to[i], &y.to[i], sizeof(cv::Point2f)) != 0) ++n;
    return n;
}

// A smooth random texture (fixed seed) and the same moved by (dx, dy) px.
std::pair<cv::Mat, cv::Mat> moved_texture(float dx, float dy) {
    cv::Mat noise(240, 320, CV_32F);
    cv::RNG rng(7);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
    cv::normalize(noise, noise, 10, 245, cv::NORM_MINMAX);
    cv::Mat a, b;
    noise.convertTo(a, CV_8U);
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
    cv::Mat moved;
    cv::warpAffine(noise, moved, shift, noise.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT_101);
    moved.convertTo(b, CV_8U);
    return {a, b};
}

// The first n colour frames of a TUM-layout sequence, grey.
std::vector<cv::Mat> first_frames(const std::filesystem::path& dir, std::size_t n) {
    std::ifstream list(dir / "rgb.txt");
    std::vector<cv::Mat> frames;
    for (std::string line; std::getline(list, line) && frames.size() < n;)
        if (!line.empty() && line[0] != '#')
            frames.push_back(cv::imread((dir / line.substr(line.find(' ') + 1)).string(), cv::IMREAD_GRAYSCALE));
    return frames;
}

}  // namespace

TEST_CASE("track_lk: OpenCV's tracks bit for bit on a moved texture, at the true shift", "[put_vo][lk]") {
    const cv::Point2f shift(3.4f, -2.2f);
    const auto [a, b] = moved_texture(shift.x, shift.y);
    std::vector<cv::Point2f> from;
    for (int y = 0; y < a.rows; y += 9)
        for (int x = 0; x < a.cols; x += 9) from.emplace_back(static_cast<float>(x) + 0.3f, static_cast<float>(y) + 0.6f);
    for (int w : {3, 4, 5, 7, 9}) {  // 3–7: the bit-exact SIMD path; 9: handed to OpenCV
        put_vo::LkOptions o;
        o.window = cv::Size(w, w);
        const std::vector<cv::Mat> pa = pyramid(a, o.window, o.levels), pb = pyramid(b, o.window, o.levels);
        for (bool initial : {false, true}) {
            o.use_initial_flow = initial;
            std::vector<cv::Point2f> start = from;
            if (initial)
                for (cv::Point2f& p : start) p += cv::Point2f(2.5f, -1.5f);  // a prior near the motion
            const Tracks cv_tracks = with_opencv(pa, pb, from, start, o);
            const Tracks own = with_own(pa, pb, from, start, o);
            INFO("window " << w << ", initial flow " << initial);
            CHECK(differing(cv_tracks, own) == 0);
            // And the tracks are right: interior points land on the true shift.
            std::vector<double> errors;
            for (std::size_t i = 0; i < from.size(); ++i)
                if (own.status[i] && from[i].x > 20 && from[i].y > 20 && from[i].x < a.cols - 20 && from[i].y < a.rows - 20)
                    errors.push_back(cv::norm(own.to[i] - from[i] - shift));
            REQUIRE(errors.size() > 300);
            std::nth_element(errors.begin(), errors.begin() + static_cast<long>(errors.size() / 2), errors.end());
            CHECK(errors[errors.size() / 2] < 0.1);
        }
    }
}

TEST_CASE("track_lk: OpenCV's tracks bit for bit on real fr1/rpy frames", "[put_vo][lk]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    const std::vector<cv::Mat> frames = first_frames(dir, 12);
    REQUIRE(frames.size() == 12);
    put_vo::LkOptions o;  // put_vo's settings: 7-px window, two levels above the base, 30 iterations, ε 0.01
    std::size_t compared = 0, tracked = 0;
    for (std::size_t k = 1; k < frames.size(); ++k) {
        std::vector<cv::Point2f> from;
        cv::goodFeaturesToTrack(frames[k - 1], from, 400, 0.01, 8);
        const std::vector<cv::Mat> pa = pyramid(frames[k - 1], o.window, o.levels), pb = pyramid(frames[k], o.window, o.levels);
        for (bool initial : {false, true}) {
            o.use_initial_flow = initial;
            std::vector<cv::Point2f> start = from;
            if (initial)  // the backward check's start: the forward result
                start = with_opencv(pa, pb, from, from, put_vo::LkOptions{}).to;
            const Tracks cv_tracks = with_opencv(pa, pb, from, start, o);
            const Tracks own = with_own(pa, pb, from, start, o);
            INFO("frames " << k - 1 << "→" << k << ", initial flow " << initial);
            CHECK(differing(cv_tracks, own) == 0);
            compared += from.size();
            for (unsigned char s : own.status) tracked += s;
        }
    }
    CHECK(tracked > compared / 2);
}

TEST_CASE("track_lk: points off the image fail as OpenCV fails them; a pyramid without the border is refused", "[put_vo][lk]") {
    const auto [a, b] = moved_texture(1.0f, 0.5f);
    put_vo::LkOptions o;
    const std::vector<cv::Mat> pa = pyramid(a, o.window, o.levels), pb = pyramid(b, o.window, o.levels);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::vector<cv::Point2f> hostile = {{-1000, 5}, {5, 1e9f}, {nan, 10}, {10, inf}, {-0.0f, 0}, {319.9f, 239.9f}};
    const Tracks own = with_own(pa, pb, hostile, hostile, o);
    const Tracks cv_tracks = with_opencv(pa, pb, hostile, hostile, o);
    CHECK(own.status == cv_tracks.status);
    for (std::size_t i = 0; i < 4; ++i) CHECK(own.status[i] == 0);

    // Built with OpenCV's own border for the window (7 px): too narrow for the 8-lane reads.
    std::vector<cv::Mat> narrow;
    cv::buildOpticalFlowPyramid(a, narrow, o.window, o.levels);
    std::vector<cv::Point2f> to;
    std::vector<unsigned char> status;
    CHECK_THROWS_WITH(put_vo::track_lk(narrow, pb, hostile, to, status, o), Catch::Contains("border under 9 px"));
    o.use_initial_flow = true;
    to.clear();
    CHECK_THROWS_WITH(put_vo::track_lk(pa, pb, hostile, to, status, o), Catch::Contains("start for every point"));
}

// integer_sums: the window sums exact in integer lanes — OpenCV's tracks up to its float rounding,
// which can only move a search's stopping point by about a step under ε.
TEST_CASE("track_lk: integer sums keep OpenCV's tracks to a fraction of ε on real fr1/rpy frames", "[put_vo][lk]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    const std::vector<cv::Mat> frames = first_frames(dir, 12);
    REQUIRE(frames.size() == 12);
    put_vo::LkOptions o;
    o.integer_sums = true;
    std::vector<double> moved;  // how far each track lies from OpenCV's, px
    std::size_t both = 0, either = 0;
    for (std::size_t k = 1; k < frames.size(); ++k) {
        std::vector<cv::Point2f> from;
        cv::goodFeaturesToTrack(frames[k - 1], from, 400, 0.01, 8);
        const std::vector<cv::Mat> pa = pyramid(frames[k - 1], o.window, o.levels), pb = pyramid(frames[k], o.window, o.levels);
        const Tracks cv_tracks = with_opencv(pa, pb, from, from, o);
        const Tracks own = with_own(pa, pb, from, from, o);
        for (std::size_t i = 0; i < from.size(); ++i) {
            either += cv_tracks.status[i] || own.status[i];
            if (!cv_tracks.status[i] || !own.status[i]) continue;
            ++both;
            moved.push_back(cv::norm(cv_tracks.to[i] - own.to[i]));
        }
    }
    INFO(both << " of " << either << " tracked by both");
    CHECK(static_cast<double>(both) >= 0.99 * static_cast<double>(either));
    REQUIRE(moved.size() > 2000);
    std::sort(moved.begin(), moved.end());
    const double median = moved[moved.size() / 2], p95 = moved[moved.size() * 95 / 100];
    INFO("median " << median << " px, 95th percentile " << p95 << " px");
    CHECK(median < 1e-3);  // float rounding only (measured 9e-5 at the 80th percentile)
    CHECK(p95 < 0.01);     // a search stopping a step earlier or later: under ε (measured 0.0012)
}

// The integer sums' bound: a window of the largest values and derivatives there are (full-contrast
// stripes against their negative) sums exactly, as the float sums do to their rounding.
TEST_CASE("track_lk: integer sums do not overflow at full contrast", "[put_vo][lk]") {
    cv::Mat a(64, 64, CV_8U), b;
    for (int y = 0; y < a.rows; ++y)
        for (int x = 0; x < a.cols; ++x) a.at<uchar>(y, x) = ((x / 2 + y / 3) % 2) ? 255 : 0;
    b = 255 - a;
    put_vo::LkOptions o;
    o.levels = 0;
    o.max_iterations = 1;
    o.min_eigen = 0;
    const std::vector<cv::Mat> pa = pyramid(a, o.window, o.levels), pb = pyramid(b, o.window, o.levels);
    std::vector<cv::Point2f> from;
    for (int y = 12; y < 52; y += 5)
        for (int x = 12; x < 52; x += 5) from.emplace_back(static_cast<float>(x) + 0.25f, static_cast<float>(y) + 0.5f);
    const Tracks exact = with_own(pa, pb, from, from, o);
    o.integer_sums = true;
    const Tracks integer = with_own(pa, pb, from, from, o);
    std::size_t compared = 0;
    for (std::size_t i = 0; i < from.size(); ++i) {
        REQUIRE(integer.status[i] == exact.status[i]);
        if (!exact.status[i]) continue;
        ++compared;
        CHECK(std::abs(integer.to[i].x - exact.to[i].x) < 1e-3);
        CHECK(std::abs(integer.to[i].y - exact.to[i].y) < 1e-3);
    }
    CHECK(compared > 30);
}
