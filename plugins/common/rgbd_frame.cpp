#include "rgbd_frame.hpp"

#include <vobench/plugin.hpp>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

namespace vobench::rgbd {

cv::Mat wrap(const vobench_image& image) {
    int type;
    switch (image.format) {
        case VOBENCH_PIXEL_RGB8:
        case VOBENCH_PIXEL_BGR8: type = CV_8UC3; break;
        case VOBENCH_PIXEL_GRAY8: type = CV_8UC1; break;
        case VOBENCH_PIXEL_DEPTH_U16: type = CV_16UC1; break;
        case VOBENCH_PIXEL_DEPTH_F32: type = CV_32FC1; break;
        default: throw sdk::Error(VOBENCH_INVALID_ARGUMENT, "unsupported pixel format " + std::to_string(image.format));
    }
    return cv::Mat(image.height, image.width, type, const_cast<void*>(image.data), static_cast<std::size_t>(image.stride_bytes));
}

void to_gray(const vobench_image& image, cv::Mat& gray) {
    const cv::Mat m = wrap(image);
    if (image.format == VOBENCH_PIXEL_BGR8)
        cv::cvtColor(m, gray, cv::COLOR_BGR2GRAY);
    else if (image.format == VOBENCH_PIXEL_RGB8)
        cv::cvtColor(m, gray, cv::COLOR_RGB2GRAY);
    else if (image.format == VOBENCH_PIXEL_GRAY8)
        m.copyTo(gray);
    else
        throw sdk::Error(VOBENCH_INVALID_ARGUMENT, "colour image has a depth pixel format");
}

double depth_at(const cv::Mat& depth, double scale, const cv::Point2f& p, const DepthRange& range) {
    const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
    if (x < 1 || y < 1 || x >= depth.cols - 1 || y >= depth.rows - 1) return NAN;
    double lo = 1e9, hi = 0, centre = 0;
    double window[3][3];
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const double d =
                depth.type() == CV_16UC1 ? depth.at<uint16_t>(y + dy, x + dx) * scale : depth.at<float>(y + dy, x + dx) * scale;
            if (!(d > 0)) return NAN;
            lo = std::min(lo, d);
            hi = std::max(hi, d);
            window[dy + 1][dx + 1] = d;
            if (dx == 0 && dy == 0) centre = d;
        }
    if (centre < range.min_m || centre > range.max_m || hi - lo > 0.05 * centre) return NAN;
    if (!range.interpolate) return centre;
    // Bilinear at the sub-pixel position, from the 2×2 pixels around it (inside the smooth window).
    const double fx = p.x - x, fy = p.y - y;  // in [−0.5, 0.5]
    const int ix = fx < 0 ? 0 : 1, iy = fy < 0 ? 0 : 1;
    const double ax = fx < 0 ? fx + 1 : fx, ay = fy < 0 ? fy + 1 : fy;
    return (1 - ay) * ((1 - ax) * window[iy][ix] + ax * window[iy][ix + 1]) +
           ay * ((1 - ax) * window[iy + 1][ix] + ax * window[iy + 1][ix + 1]);
}

std::vector<Eigen::Vector3d> back_project(const cv::Mat& depth, double scale, const std::vector<cv::Point2f>& pixels, const cv::Matx33d& K,
                                          const cv::Mat& distortion, const DepthRange& range) {
    std::vector<cv::Point2f> normalised;
    if (!pixels.empty()) cv::undistortPoints(pixels, normalised, K, distortion);
    std::vector<Eigen::Vector3d> points(pixels.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const double z = depth_at(depth, scale, pixels[i], range);
        points[i] = std::isnan(z) ? Eigen::Vector3d::Constant(NAN) : Eigen::Vector3d(normalised[i].x * z, normalised[i].y * z, z);
    }
    return points;
}

cv::Matx33d camera_matrix(const vobench_camera& c) { return {c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1}; }

cv::Mat distortion_of(const vobench_camera& c) {
    cv::Mat d(1, std::max(0, c.distortion_count), CV_64F);
    for (int i = 0; i < c.distortion_count; ++i) d.at<double>(0, i) = c.distortion[i];
    return d;
}

cv::Point2f at_middle_row(const cv::Point2f& pixel, const cv::Point2f& flow, int rows, double readout_s, double interval_s) {
    if (!(readout_s > 0) || !(interval_s > 0) || rows <= 0) return pixel;
    const double lag = (pixel.y / rows - 0.5) * readout_s / interval_s;  // in frame intervals
    return {static_cast<float>(pixel.x - lag * flow.x), static_cast<float>(pixel.y - lag * flow.y)};
}

void write_pose(const Eigen::Isometry3d& T, vobench_pose& pose) {
    const Eigen::Quaterniond q(T.linear());
    pose.tx = T.translation().x();
    pose.ty = T.translation().y();
    pose.tz = T.translation().z();
    pose.qx = q.x();
    pose.qy = q.y();
    pose.qz = q.z();
    pose.qw = q.w();
}

}  // namespace vobench::rgbd
