// orb_matching — the "matching-based approach" Kraft et al. (2016, §5.1) contrast their tracker with:
// ORB key points and descriptors in every frame, brute-force Hamming matching with Lowe's ratio test
// between consecutive frames, depth at both ends, and the same 3-point RANSAC + Umeyama as put_vo
// (plugins/common/rigid_ransac). Poses chain frame to frame.
#include "rgbd_frame.hpp"    // plugins/common
#include "rigid_ransac.hpp"  // plugins/common

#include <vobench/plugin.hpp>

#include <opencv2/features2d.hpp>

#include <random>

namespace {

using vobench::sdk::Host;

class OrbMatching : public vobench::sdk::Odometry {
public:
    static vobench::sdk::PluginInfo info() {
        return {"orb_matching",
                "1.0.0",
                "Feature-matching VO: ORB in every frame, Hamming matching with a ratio test, 3-point RANSAC + Umeyama.",
                "MIT",
                "",
                {{"features", VOBENCH_PARAM_INT, "1000", 50, 20000, "", "ORB features per frame"},
                 {"scale_levels", VOBENCH_PARAM_INT, "8", 1, 16, "", "ORB pyramid levels"},
                 {"ratio", VOBENCH_PARAM_DOUBLE, "0.8", 0.1, 1.0, "", "Lowe's ratio test: best / second best distance"},
                 {"ransac_threshold", VOBENCH_PARAM_DOUBLE, "0.035", 0.001, 1, "", "RANSAC inlier distance, m"},
                 {"min_inliers", VOBENCH_PARAM_INT, "10", 3, 10000, "", "below this the frame is lost"},
                 {"depth_min", VOBENCH_PARAM_DOUBLE, "0.1", 0, 100, "", "depth accepted from, m"},
                 {"depth_max", VOBENCH_PARAM_DOUBLE, "6.0", 0, 100, "", "depth accepted up to, m"}}};
    }

    void start(const vobench_camera& camera, const vobench::sdk::Params& p, uint64_t seed) override {
        K_ = vobench::rgbd::camera_matrix(camera);
        dist_ = vobench::rgbd::distortion_of(camera);
        orb_ = cv::ORB::create(static_cast<int>(p.get_int("features")), 1.2f, static_cast<int>(p.get_int("scale_levels")));
        ratio_ = p.get_double("ratio");
        ransac_.inlier_threshold_m = p.get_double("ransac_threshold");
        min_inliers_ = static_cast<int>(p.get_int("min_inliers"));
        range_ = {p.get_double("depth_min"), p.get_double("depth_max")};
        rng_.seed(seed);
        reset();
    }

    void reset() override {
        previous_points_.clear();
        previous_descriptors_.release();
        world_from_current_ = Eigen::Isometry3d::Identity();
    }

    vobench_tracking_status process(const vobench_frame& frame, vobench_pose& pose) override {
        vobench::rgbd::to_gray(*frame.color, gray_);
        std::vector<cv::KeyPoint> keypoints;
        cv::Mat descriptors;
        {
            Host::Stage s(host(), "detection");
            orb_->detectAndCompute(gray_, cv::noArray(), keypoints, descriptors);
        }
        host().counter("features_detected", static_cast<double>(keypoints.size()));
        std::vector<cv::Point2f> pixels;
        for (const auto& k : keypoints) pixels.push_back(k.pt);
        std::vector<Eigen::Vector3d> points;
        {
            Host::Stage s(host(), "depth_association");
            points = vobench::rgbd::back_project(vobench::rgbd::wrap(*frame.depth), frame.depth_scale, pixels, K_, dist_, range_);
        }
        vobench_tracking_status status = VOBENCH_TRACKING_OK;
        if (!previous_points_.empty() && !descriptors.empty()) {
            std::vector<Eigen::Vector3d> from, to;
            {
                Host::Stage s(host(), "matching");
                std::vector<std::vector<cv::DMatch>> knn;
                matcher_.knnMatch(descriptors, previous_descriptors_, knn, 2);
                for (const auto& m : knn) {
                    if (m.size() < 2 || m[0].distance > ratio_ * m[1].distance) continue;
                    const Eigen::Vector3d& a = points[static_cast<std::size_t>(m[0].queryIdx)];
                    const Eigen::Vector3d& b = previous_points_[static_cast<std::size_t>(m[0].trainIdx)];
                    if (std::isnan(a.x()) || std::isnan(b.x())) continue;
                    from.push_back(a);
                    to.push_back(b);
                }
            }
            host().counter("matches", static_cast<double>(from.size()));
            Host::Stage s(host(), "estimation");
            const vobench::rigid::RansacResult r = vobench::rigid::ransac_rigid(from, to, ransac_, rng_);
            host().counter("inliers", static_cast<double>(r.inliers.size()));
            if (r.ok && static_cast<int>(r.inliers.size()) >= min_inliers_)
                world_from_current_ = world_from_current_ * r.transform;
            else
                status = VOBENCH_TRACKING_LOST;  // hold the pose; match the next frame against this one
        }
        previous_points_ = std::move(points);
        previous_descriptors_ = descriptors;
        vobench::rgbd::write_pose(world_from_current_, pose);
        return status;
    }

private:
    cv::Matx33d K_;
    cv::Mat dist_;
    cv::Ptr<cv::ORB> orb_;
    cv::BFMatcher matcher_{cv::NORM_HAMMING};
    double ratio_ = 0.8;
    int min_inliers_ = 10;
    vobench::rgbd::DepthRange range_;
    vobench::rigid::RansacOptions ransac_;
    std::mt19937_64 rng_;
    cv::Mat gray_, previous_descriptors_;
    std::vector<Eigen::Vector3d> previous_points_;
    Eigen::Isometry3d world_from_current_ = Eigen::Isometry3d::Identity();
};

}  // namespace

VOBENCH_ODOMETRY_PLUGIN(OrbMatching)
