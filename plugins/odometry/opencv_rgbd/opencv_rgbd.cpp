// opencv_rgbd — the dense baselines of OpenCV contrib's rgbd module, frame to frame:
//   rgbd      cv::rgbd::RgbdOdometry     photometric + depth (Steinbrücker et al. 2011)
//   icp       cv::rgbd::ICPOdometry      point-to-plane ICP on depth only
//   rgbd_icp  cv::rgbd::RgbdICPOdometry  both terms
//   fast_icp  cv::rgbd::FastICPOdometry  KinectFusion-style ICP
// OpenCV's Rt maps points of the previous frame into the current one, so the pose chains as
// world_from_current = world_from_previous · Rt⁻¹. Images are used as delivered (OpenCV's odometry
// assumes a pinhole camera; lens distortion is ignored, as OpenCV's samples do).
#include "rgbd_frame.hpp"  // plugins/common

#include <vobench/plugin.hpp>

#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd.hpp>

#include <Eigen/Geometry>

namespace {

using vobench::sdk::Host;

class OpenCvRgbd : public vobench::sdk::Odometry {
public:
    static vobench::sdk::PluginInfo info() {
        return {"opencv_rgbd",
                "1.0.0",
                "OpenCV contrib dense RGB-D odometry (RgbdOdometry, ICPOdometry, RgbdICPOdometry, FastICPOdometry), frame to frame.",
                "Apache-2.0",
                "https://docs.opencv.org/4.6.0/d7/d83/classcv_1_1rgbd_1_1Odometry.html",
                {{"method", VOBENCH_PARAM_ENUM, "rgbd", 0, 0, "rgbd|icp|rgbd_icp|fast_icp", "which OpenCV odometry"},
                 {"min_depth", VOBENCH_PARAM_DOUBLE, "0.1", 0, 100, "", "depth used from, m"},
                 {"max_depth", VOBENCH_PARAM_DOUBLE, "6.0", 0, 100, "", "depth used up to, m"},
                 {"max_depth_diff", VOBENCH_PARAM_DOUBLE, "0.07", 0.001, 10, "", "largest depth difference of a correspondence, m"},
                 {"max_points_part", VOBENCH_PARAM_DOUBLE, "0.07", 0.001, 1, "", "fraction of pixels used (rgbd, icp, rgbd_icp)"}}};
    }

    void start(const vobench_camera& camera, const vobench::sdk::Params& p, uint64_t) override {
        const std::string method = p.get_string("method");
        const cv::Mat K = (cv::Mat_<float>(3, 3) << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
        const float min_depth = static_cast<float>(p.get_double("min_depth")), max_depth = static_cast<float>(p.get_double("max_depth"));
        const float diff = static_cast<float>(p.get_double("max_depth_diff")), part = static_cast<float>(p.get_double("max_points_part"));
        if (method == "rgbd")
            odometry_ = cv::makePtr<cv::rgbd::RgbdOdometry>(K, min_depth, max_depth, diff, std::vector<int>(), std::vector<float>(), part);
        else if (method == "icp")
            odometry_ = cv::makePtr<cv::rgbd::ICPOdometry>(K, min_depth, max_depth, diff, part);
        else if (method == "rgbd_icp")
            odometry_ = cv::makePtr<cv::rgbd::RgbdICPOdometry>(K, min_depth, max_depth, diff, part);
        else
            odometry_ = cv::makePtr<cv::rgbd::FastICPOdometry>(K, diff);
        reset();
    }

    void reset() override {
        previous_.release();
        world_from_current_ = Eigen::Isometry3d::Identity();
    }

    vobench_tracking_status process(const vobench_frame& frame, vobench_pose& pose) override {
        cv::Ptr<cv::rgbd::OdometryFrame> current;
        {
            Host::Stage s(host(), "preparation");
            current = make_frame(frame);
            odometry_->prepareFrameCache(current, cv::rgbd::OdometryFrame::CACHE_ALL);
        }
        vobench_tracking_status status = VOBENCH_TRACKING_OK;
        if (previous_) {
            Host::Stage s(host(), "estimation");
            cv::Mat Rt;
            if (odometry_->compute(previous_, current, Rt) && !Rt.empty()) {
                Eigen::Matrix4d M;
                for (int i = 0; i < 4; ++i)
                    for (int j = 0; j < 4; ++j) M(i, j) = Rt.at<double>(i, j);
                world_from_current_ = world_from_current_ * Eigen::Isometry3d(M).inverse();
            } else {
                status = VOBENCH_TRACKING_LOST;  // hold the last pose, go on from this frame
            }
        }
        previous_ = current;
        vobench::rgbd::write_pose(world_from_current_, pose);
        return status;
    }

private:
    static cv::Ptr<cv::rgbd::OdometryFrame> make_frame(const vobench_frame& frame) {
        cv::Mat gray, depth;
        vobench::rgbd::to_gray(*frame.color, gray);
        vobench::rgbd::wrap(*frame.depth).convertTo(depth, CV_32F, frame.depth_scale);  // metres
        depth.setTo(std::numeric_limits<float>::quiet_NaN(), depth == 0);               // OpenCV: NaN marks no reading
        return cv::makePtr<cv::rgbd::OdometryFrame>(gray, depth);
    }

    cv::Ptr<cv::rgbd::Odometry> odometry_;
    cv::Ptr<cv::rgbd::OdometryFrame> previous_;
    Eigen::Isometry3d world_from_current_ = Eigen::Isometry3d::Identity();
};

}  // namespace

VOBENCH_ODOMETRY_PLUGIN(OpenCvRgbd)
