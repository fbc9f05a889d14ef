// putk2 — reader for PUTK² (Kraft et al. 2016): eight sequences recorded by both Kinect v1 and
// Kinect v2 on a robot, ground truth from a ceiling camera system.
//
// Layouts (datasets/README.md): `putk2` — rgb_%05d.png, depth_%05d.png and matched.txt, as PUT's tools
// read; `putk2-tum` — rgb/, depth/, rgb.txt, depth.txt. Depth is 16-bit, `depth_unit` metres per unit
// (1 mm). Kinect v1 depth (320×240) is rescaled to the 640×480 colour image as the paper does; Kinect
// v2 depth (512×424) is registered to the 1920×1080 colour image with the depth camera's intrinsics
// and depth-to-colour pose. Intrinsics and distortion come from camData.txt (PUT's calibration ids
// 00022000 / 00033000 by default). Ground truth: groundtruth.txt (TUM layout, frame indices as
// stamps) or the raw marker trajectory composed with the camera-in-marker pose (eq. 10). PUTK² has no
// clock: stamps are frame / frame_rate seconds.
#include "putk2_files.hpp"

#include "depth_registration.hpp"  // plugins/common
#include "tum_lists.hpp"           // plugins/common

#include "metrics/association.hpp"
#include "metrics/trajectory_io.hpp"

#include "dataset_files.hpp"  // plugins/common

#include <vobench/plugin.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd.hpp>

#include <filesystem>
#include <optional>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using vobench::sdk::Error;

// PUT's calibration of the two Kinect colour cameras (camData.txt), used when a folder has none.
const vobench::putk2::CameraCalibration kPutKinect1{"00022000", 532.77250, 531.85745,
                                                    312.23007,  260.11708, {0.16054, -0.24682, 0.00136, 0.00149, 0, 0, 0, 0}};
const vobench::putk2::CameraCalibration kPutKinect2{
    "00033000",
    1078.68499,
    1076.474256,
    952.6592286,
    530.7386644,
    {0.02712800285, -0.003876435388, -0.0003782667962, -0.002409935964, 0.05862808573, -0.02856023826, 0.05860957117, 0.03897302154}};

class Putk2Reader : public vobench::sdk::Dataset {
public:
    static vobench::sdk::PluginInfo info() {
        return {
            "putk2",
            "1.0.0",
            "PUTK² (Kinect v1 and v2, Kraft et al. 2016): both layouts, depth rescaled (v1) or registered (v2) to colour.",
            "MIT",
            "https://doi.org/10.1007/s00138-016-0802-6",
            {{"sensor", VOBENCH_PARAM_ENUM, "auto", 0, 0, "auto|kinect1|kinect2", "which Kinect; auto: from the colour image size"},
             {"layout", VOBENCH_PARAM_ENUM, "auto", 0, 0, "auto|putk2|putk2-tum", "file layout; auto: matched.txt or rgb.txt"},
             {"calibration", VOBENCH_PARAM_STRING, "", 0, 0, "", "camData.txt to use (default: the folder's, else PUT's)"},
             {"camera_id", VOBENCH_PARAM_STRING, "", 0, 0, "", "camera id in camData.txt (default 00022000 / 00033000)"},
             {"depth_camera", VOBENCH_PARAM_STRING, "", 0, 0, "", "Kinect v2 depth_camera.txt (default: the folder's, else nominal)"},
             {"registration", VOBENCH_PARAM_ENUM, "splat", 0, 0, "splat|opencv",
              "Kinect v2 depth to colour: z-buffered splats, or OpenCV contrib registerDepth (sparse)"},
             {"ground_truth", VOBENCH_PARAM_ENUM, "auto", 0, 0, "auto|tum|raw|none",
              "groundtruth.txt (tum), marker trajectory.txt + camera-in-marker (raw), or none"},
             {"camera_in_marker", VOBENCH_PARAM_STRING, "", 0, 0, "", "for raw ground truth (default: the folder's cameraZnacznik.txt)"},
             {"frame_rate", VOBENCH_PARAM_DOUBLE, "10", 0.1, 1000, "", "frames per second: stamps are frame / rate"},
             {"depth_unit", VOBENCH_PARAM_DOUBLE, "0.001", 1e-6, 1, "", "metres per depth unit"},
             {"max_difference", VOBENCH_PARAM_DOUBLE, "0.02", 0.0001, 1, "", "putk2-tum: colour-depth association, seconds"}}};
    }

    void open(const std::string& path, const vobench::sdk::Params& o) override {
        root_ = path;
        if (!fs::is_directory(root_)) throw Error(VOBENCH_IO_ERROR, path + ": not a folder");
        rate_ = o.get_double("frame_rate");
        depth_unit_ = o.get_double("depth_unit");
        opencv_registration_ = o.get_string("registration") == "opencv";
        load_frames(o);
        const cv::Mat first = vobench::files::load_image(root_ / frames_.front().color, cv::IMREAD_COLOR);
        std::string sensor = o.get_string("sensor");
        if (sensor == "auto") {
            if (first.cols == 640 && first.rows == 480)
                sensor = "kinect1";
            else if (first.cols == 1920 && first.rows == 1080)
                sensor = "kinect2";
            else
                throw Error(VOBENCH_INVALID_ARGUMENT, (root_ / frames_.front().color).string() + ": cannot tell the sensor from a " +
                                                          std::to_string(first.cols) + "x" + std::to_string(first.rows) +
                                                          " image; set sensor=");
        }
        sensor_ = sensor;
        load_calibration(o, first.size());
        load_ground_truth(o);
        name_ = fs::absolute(root_).lexically_normal().filename().string();
        info_.struct_size = sizeof(info_);
        info_.name = name_.c_str();
        info_.sensor = sensor_.c_str();
        info_.camera = &camera_;
        info_.depth_width = sensor_ == "kinect1" ? 320 : 512;
        info_.depth_height = sensor_ == "kinect1" ? 240 : 424;
        info_.depth_scale = sensor_ == "kinect1" ? depth_unit_ : 1.0;
        info_.frame_count = frames_.size();
        info_.ground_truth = ground_truth_.empty() ? nullptr : ground_truth_.data();
        info_.gt_count = ground_truth_.size() / 8;
        // The ceiling-camera system's error is not stated as one figure in the paper.
        vobench::files::declare_gt_accuracy(info_, path);
    }

    const vobench_sequence_info& describe() override {
        if (frames_.empty()) throw Error(VOBENCH_ERROR, "describe() before a successful open()");
        return info_;
    }

    const vobench_frame& read_frame(uint64_t index) override {
        vobench::files::require_frame_index(index, frames_.size());
        const Frame& f = frames_[index];
        const fs::path depth_path = root_ / f.depth;
        auto images = vobench::files::load_color_and_depth(root_ / f.color, cv::IMREAD_COLOR, depth_path, cv::IMREAD_UNCHANGED);
        color_ = std::move(images.color);
        const cv::Mat raw = std::move(images.depth);
        if (color_.cols != camera_.width || color_.rows != camera_.height)
            throw Error(VOBENCH_IO_ERROR, (root_ / f.color).string() + ": " + std::to_string(color_.cols) + "x" +
                                              std::to_string(color_.rows) + ", expected " + std::to_string(camera_.width) + "x" +
                                              std::to_string(camera_.height));
        vobench::files::require_depth16(raw, depth_path);
        int32_t format;
        if (raw.size() == color_.size()) {  // already registered to colour
            depth_ = raw;
            format = VOBENCH_PIXEL_DEPTH_U16;
            frame_.depth_scale = depth_unit_;
        } else if (sensor_ == "kinect1") {
            if (raw.cols * 2 != color_.cols || raw.rows * 2 != color_.rows)
                throw Error(VOBENCH_IO_ERROR, depth_path.string() + ": Kinect v1 depth is " + std::to_string(raw.cols) + "x" +
                                                  std::to_string(raw.rows) + ", expected 320x240 or 640x480");
            // The paper rescales the 320×240 depth to the colour size; nearest: no invented depths.
            cv::resize(raw, depth_, color_.size(), 0, 0, cv::INTER_NEAREST);
            format = VOBENCH_PIXEL_DEPTH_U16;
            frame_.depth_scale = depth_unit_;
        } else {
            if (raw.cols != 512 || raw.rows != 424)
                throw Error(VOBENCH_IO_ERROR, depth_path.string() + ": Kinect v2 depth is " + std::to_string(raw.cols) + "x" +
                                                  std::to_string(raw.rows) + ", expected 512x424 or 1920x1080");
            depth_ = register_v2(raw);
            format = VOBENCH_PIXEL_DEPTH_F32;
            frame_.depth_scale = 1.0;
        }
        color_image_ = vobench::files::image_of(color_, VOBENCH_PIXEL_BGR8);
        depth_image_ = vobench::files::image_of(depth_, format);
        frame_.struct_size = sizeof(frame_);
        frame_.index = index;
        frame_.timestamp = f.stamp;
        frame_.depth_timestamp = f.depth_stamp;
        frame_.color = &color_image_;
        frame_.depth = &depth_image_;
        return frame_;
    }

private:
    struct Frame {
        double stamp, depth_stamp;
        std::string color, depth;
    };

    void load_frames(const vobench::sdk::Params& o) {
        std::string layout = o.get_string("layout");
        if (layout == "auto") layout = fs::exists(root_ / "matched.txt") ? "putk2" : fs::exists(root_ / "rgb.txt") ? "putk2-tum" : "";
        if (layout.empty()) throw Error(VOBENCH_IO_ERROR, root_.string() + ": neither matched.txt nor rgb.txt: not a PUTK² sequence");
        if (layout == "putk2") {
            const fs::path list = root_ / "matched.txt";
            for (const auto& m :
                 vobench::files::parsed([&] { return vobench::putk2::parse_matched(vobench::files::read_text(list), list.string()); })) {
                const double t = static_cast<double>(m.id) / rate_;
                frames_.push_back({t, t, m.color, m.depth});
            }
            return;
        }
        const fs::path rgb_path = root_ / "rgb.txt", depth_path = root_ / "depth.txt";
        const auto rgb =
            vobench::files::parsed([&] { return vobench::tum::parse_list(vobench::files::read_text(rgb_path), rgb_path.string()); });
        const auto depth =
            vobench::files::parsed([&] { return vobench::tum::parse_list(vobench::files::read_text(depth_path), depth_path.string()); });
        std::vector<double> a, b;
        for (const auto& e : rgb) a.push_back(e.stamp);
        for (const auto& e : depth) b.push_back(e.stamp);
        vobench::metrics::AssociationOptions assoc;
        assoc.max_difference = o.get_double("max_difference");
        const auto matches = vobench::files::parsed([&] { return vobench::metrics::associate(a, b, assoc).matches; });
        for (const auto& m : matches)
            frames_.push_back({rgb[m.first].stamp, depth[m.second].stamp, rgb[m.first].path, depth[m.second].path});
    }

    void load_calibration(const vobench::sdk::Params& o, cv::Size color_size) {
        std::string file = o.get_string("calibration");
        if (file.empty() && fs::exists(root_ / "camData.txt")) file = (root_ / "camData.txt").string();
        std::string id = o.get_string("camera_id");
        if (id.empty()) id = sensor_ == "kinect1" ? kPutKinect1.id : kPutKinect2.id;
        vobench::putk2::CameraCalibration cal = sensor_ == "kinect1" ? kPutKinect1 : kPutKinect2;
        if (!file.empty()) {
            const auto cameras =
                vobench::files::parsed([&] { return vobench::putk2::parse_cam_data(vobench::files::read_text(file), file); });
            bool found = false;
            std::string ids;
            for (const auto& c : cameras) {
                ids += (ids.empty() ? "" : ", ") + c.id;
                if (c.id == id) {
                    cal = c;
                    found = true;
                }
            }
            if (!found) throw Error(VOBENCH_INVALID_ARGUMENT, file + ": no camera " + id + " (it has " + ids + "); set camera_id=");
        } else if (id != cal.id) {
            throw Error(VOBENCH_INVALID_ARGUMENT, "camera_id=" + id + " needs a calibration file with that camera");
        }
        camera_.struct_size = sizeof(camera_);
        camera_.width = color_size.width;
        camera_.height = color_size.height;
        camera_.fx = cal.fx;
        camera_.fy = cal.fy;
        camera_.cx = cal.cx;
        camera_.cy = cal.cy;
        camera_.distortion_model = VOBENCH_DISTORTION_OPENCV;
        camera_.distortion_count = 8;
        for (int i = 0; i < 8; ++i) camera_.distortion[i] = cal.distortion[static_cast<std::size_t>(i)];
        color_intrinsics_ = {cal.fx, cal.fy, cal.cx, cal.cy, 8, cal.distortion};
        if (sensor_ == "kinect2") {
            std::string depth_file = o.get_string("depth_camera");
            if (depth_file.empty() && fs::exists(root_ / "depth_camera.txt")) depth_file = (root_ / "depth_camera.txt").string();
            if (!depth_file.empty()) {
                depth_camera_ = vobench::files::parsed(
                    [&] { return vobench::putk2::parse_depth_camera(vobench::files::read_text(depth_file), depth_file); });
            } else {
                // Nominal Kinect v2 depth camera (≈70°×60°), 5.2 cm beside the colour camera.
                depth_camera_ = {365.5, 365.5, 255.5, 211.5, Eigen::Isometry3d::Identity()};
                depth_camera_.in_color.translation() = Eigen::Vector3d(0.052, 0, 0);
                host().warn("no depth_camera.txt: using nominal Kinect v2 depth intrinsics and a 5.2 cm baseline");
            }
            const vobench::rgbd::Intrinsics d{depth_camera_.fx, depth_camera_.fy, depth_camera_.cx, depth_camera_.cy, 0, {}};
            registration_.emplace(d, color_intrinsics_, depth_camera_.in_color, cv::Size(512, 424), color_size);
        }
    }

    void load_ground_truth(const vobench::sdk::Params& o) {
        std::string which = o.get_string("ground_truth");
        if (which == "auto") which = fs::exists(root_ / "groundtruth.txt") ? "tum" : fs::exists(root_ / "trajectory.txt") ? "raw" : "none";
        if (which == "none") return;
        vobench::metrics::ReadOptions ro;
        fs::path file = root_ / "groundtruth.txt";
        if (which == "raw") {
            ro.format = vobench::metrics::TrajectoryFormat::Putk2Raw;
            file = root_ / "trajectory.txt";
            const std::string cim =
                o.get_string("camera_in_marker").empty() ? (root_ / "cameraZnacznik.txt").string() : o.get_string("camera_in_marker");
            ro.camera_in_marker = vobench::files::parsed([&] { return vobench::metrics::read_camera_in_marker(cim); });
        }
        const auto gt = vobench::files::parsed([&] { return vobench::metrics::read_trajectory(file, ro); });
        for (const std::string& w : gt.warnings) host().warn(w);
        for (const auto& p : gt.poses)  // frame indices → seconds
            ground_truth_.insert(ground_truth_.end(), {p.t / rate_, p.p.x(), p.p.y(), p.p.z(), p.q.x(), p.q.y(), p.q.z(), p.q.w()});
    }

    cv::Mat register_v2(const cv::Mat& raw) const {
        cv::Mat metres;
        raw.convertTo(metres, CV_32F, depth_unit_);
        if (!opencv_registration_) {
            return (*registration_)(metres);
        }
        const cv::Matx33d Kd(depth_camera_.fx, 0, depth_camera_.cx, 0, depth_camera_.fy, depth_camera_.cy, 0, 0, 1);
        const cv::Matx33d Kc(camera_.fx, 0, camera_.cx, 0, camera_.fy, camera_.cy, 0, 0, 1);
        cv::Matx44d Rt;
        const Eigen::Matrix4d M = depth_camera_.in_color.matrix();
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) Rt(i, j) = M(i, j);
        cv::Mat registered;
        cv::rgbd::registerDepth(Kd, Kc, cv::Mat(1, 8, CV_64F, const_cast<double*>(camera_.distortion)), Rt, metres, color_.size(),
                                registered, true);
        registered.setTo(0, registered != registered);  // NaN (no reading) → 0
        return registered;
    }

    fs::path root_;
    std::vector<Frame> frames_;
    std::vector<double> ground_truth_;
    std::string name_, sensor_;
    double rate_ = 10, depth_unit_ = 0.001;
    bool opencv_registration_ = false;
    vobench_camera camera_{};
    vobench::rgbd::Intrinsics color_intrinsics_;
    vobench::putk2::DepthCamera depth_camera_;
    std::optional<vobench::rgbd::DepthRegistration> registration_;  // Kinect v2, set up once by open()
    vobench_sequence_info info_{};
    cv::Mat color_, depth_;
    vobench_image color_image_{}, depth_image_{};
    vobench_frame frame_{};
};

}  // namespace

VOBENCH_DATASET_PLUGIN(Putk2Reader)
