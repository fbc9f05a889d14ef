// open3d_rgbd — Open3D's RGB-D odometry (open3d::pipelines::odometry, Open3D 0.16, MIT), frame to frame:
//   color   photometric term only (Steinbrücker, Sturm & Cremers 2011, "Real-time visual odometry from
//           dense RGB-D images") — Open3D's RGBDOdometryJacobianFromColorTerm
//   hybrid  photometric + geometric term (Park, Zhou & Koltun 2017, "Colored point cloud registration
//           revisited", as Open3D implements it for RGB-D) — RGBDOdometryJacobianFromHybridTerm
// These are the dense, DVO-like methods the RGB-D odometry literature compares against, a second
// family beside OpenCV's four. Open3D's transform maps the source frame's points into the target's;
// with source = current and target = previous it is previous_from_current, so the pose chains as
// world_from_current = world_from_previous · T. Each search starts from the last motion (constant
// velocity), as Open3D's own reconstruction pipeline seeds it. Lens distortion is ignored (pinhole),
// as with opencv_rgbd. This is the legacy pipeline: the tensor one (t::pipelines::odometry) cannot run
// its colour terms in Debian's build ("RGBToGray … on device CPU:0 is not implemented", without IPP).
#include "rgbd_frame.hpp"  // plugins/common

#include <vobench/plugin.hpp>

#include <open3d/camera/PinholeCameraIntrinsic.h>
#include <open3d/geometry/Image.h>
#include <open3d/geometry/RGBDImage.h>
#include <open3d/pipelines/odometry/Odometry.h>
#include <open3d/pipelines/odometry/RGBDOdometryJacobian.h>
#include <open3d/utility/Logging.h>

#include <opencv2/imgproc.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace {

using vobench::sdk::Host;
namespace o3d = open3d;

class Open3dRgbd : public vobench::sdk::Odometry {
public:
    static vobench::sdk::PluginInfo info() {
        return {"open3d_rgbd",
                "1.0.0",
                "Open3D dense RGB-D odometry (colour term: Steinbrücker et al. 2011; hybrid colour + depth term), frame to frame.",
                "MIT",
                "https://www.open3d.org/docs/0.16.0/tutorial/pipelines/rgbd_odometry.html",
                {{"term", VOBENCH_PARAM_ENUM, "hybrid", 0, 0, "color|hybrid", "Jacobian: colour term only, or colour + depth"},
                 {"min_depth", VOBENCH_PARAM_DOUBLE, "0.1", 0, 100, "", "depth used from, m"},
                 {"max_depth", VOBENCH_PARAM_DOUBLE, "6.0", 0, 100, "", "depth used up to, m (Open3D's default: 4)"},
                 {"max_depth_diff", VOBENCH_PARAM_DOUBLE, "0.07", 0.001, 10, "",
                  "largest depth difference of a correspondence, m (Open3D's default 0.03; 0.07 as opencv_rgbd, for fast motion)"},
                 {"iterations", VOBENCH_PARAM_STRING, "20,10,5", 0, 0, "",
                  "Gauss-Newton iterations per pyramid level, coarsest first (Open3D's default)"},
                 {"motion_prior", VOBENCH_PARAM_BOOL, "true", 0, 0, "", "start each search from the last frame-to-frame motion"}}};
    }

    void start(const vobench_camera& camera, const vobench::sdk::Params& p, uint64_t) override {
        // Open3D would print per-frame warnings; its verbosity is process-wide, and the cell process is this plugin's.
        o3d::utility::SetVerbosityLevel(o3d::utility::VerbosityLevel::Error);
        intrinsic_ = o3d::camera::PinholeCameraIntrinsic(camera.width, camera.height, camera.fx, camera.fy, camera.cx, camera.cy);
        option_ = o3d::pipelines::odometry::OdometryOption(parse_iterations(p.get_string("iterations")), p.get_double("max_depth_diff"),
                                                           p.get_double("min_depth"), p.get_double("max_depth"));
        if (p.get_string("term") == "color")
            jacobian_ = std::make_unique<o3d::pipelines::odometry::RGBDOdometryJacobianFromColorTerm>();
        else
            jacobian_ = std::make_unique<o3d::pipelines::odometry::RGBDOdometryJacobianFromHybridTerm>();
        motion_prior_ = p.get_bool("motion_prior");
        reset();
    }

    void reset() override {
        previous_.reset();
        world_from_current_ = Eigen::Isometry3d::Identity();
        last_motion_ = Eigen::Matrix4d::Identity();
    }

    vobench_tracking_status process(const vobench_frame& frame, vobench_pose& pose) override {
        cv::Mat intensity, depth;  // grey levels (8 bit), depth in metres (0: none)
        {
            Host::Stage s(host(), "preparation");
            vobench::rgbd::to_gray(*frame.color, intensity);
            vobench::rgbd::wrap(*frame.depth).convertTo(depth, CV_32F, frame.depth_scale);
            // No reading as 0; Open3D itself drops depths outside [depth_min, depth_max] (OdometryOption).
            depth.setTo(0, (depth != depth) | (depth < 0));
            current_ = make_rgbd(intensity, depth);
        }
        vobench_tracking_status status = VOBENCH_TRACKING_OK;
        if (previous_) {
            Host::Stage s(host(), "estimation");
            const Eigen::Matrix4d init = motion_prior_ ? last_motion_ : Eigen::Matrix4d::Identity();
            bool ok = false;
            Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
            std::tie(ok, T, std::ignore) =
                o3d::pipelines::odometry::ComputeRGBDOdometry(*current_, *previous_, intrinsic_, init, *jacobian_, option_);
            if (ok && T.allFinite()) {
                world_from_current_ = world_from_current_ * Eigen::Isometry3d(T);
                last_motion_ = T;
            } else {
                status = VOBENCH_TRACKING_LOST;  // hold the last pose, go on from this frame
                last_motion_ = Eigen::Matrix4d::Identity();
            }
        }
        std::swap(previous_, current_);
        vobench::rgbd::write_pose(world_from_current_, pose);
        return status;
    }

private:
    // "20,10,5" → {20, 10, 5}; each a positive count.
    static std::vector<int> parse_iterations(const std::string& text) {
        std::vector<int> out;
        std::size_t at = 0;
        while (at <= text.size()) {
            const std::size_t comma = std::min(text.find(',', at), text.size());
            const std::string item = text.substr(at, comma - at);
            char* end = nullptr;
            const long n = std::strtol(item.c_str(), &end, 10);
            if (item.empty() || *end != '\0' || n < 1 || n > 1000)
                throw vobench::sdk::Error(VOBENCH_INVALID_ARGUMENT,
                                          "iterations: '" + text + "' is not a comma-separated list of counts 1…1000");
            out.push_back(static_cast<int>(n));
            at = comma + 1;
        }
        if (out.size() > 8) throw vobench::sdk::Error(VOBENCH_INVALID_ARGUMENT, "iterations: at most 8 pyramid levels");
        return out;
    }

    // The legacy pipeline wants one-channel float images: intensity in [0, 1] and depth in metres.
    static o3d::geometry::RGBDImage make_rgbd(const cv::Mat& gray, const cv::Mat& depth) {
        cv::Mat intensity;
        gray.convertTo(intensity, CV_32F, 1.0 / 255.0);
        o3d::geometry::RGBDImage rgbd;
        copy_into(intensity, rgbd.color_);
        copy_into(depth, rgbd.depth_);
        return rgbd;
    }

    static void copy_into(const cv::Mat& m, o3d::geometry::Image& image) {
        image.Prepare(m.cols, m.rows, 1, 4);
        for (int y = 0; y < m.rows; ++y)
            std::memcpy(image.data_.data() + static_cast<std::size_t>(y) * m.cols * 4, m.ptr<float>(y),
                        static_cast<std::size_t>(m.cols) * 4);
    }

    o3d::camera::PinholeCameraIntrinsic intrinsic_;
    o3d::pipelines::odometry::OdometryOption option_;
    std::unique_ptr<o3d::pipelines::odometry::RGBDOdometryJacobian> jacobian_;
    bool motion_prior_ = true;
    std::optional<o3d::geometry::RGBDImage> current_, previous_;
    Eigen::Isometry3d world_from_current_ = Eigen::Isometry3d::Identity();
    Eigen::Matrix4d last_motion_ = Eigen::Matrix4d::Identity();
};

}  // namespace

VOBENCH_ODOMETRY_PLUGIN(Open3dRgbd)
