// tum — reader for the TUM RGB-D benchmark layout (Sturm et al., IROS 2012).
//
// A sequence folder holds rgb.txt, depth.txt (`timestamp path` lines) and, usually, groundtruth.txt
// (`t tx ty tz qx qy qz qw`). Colour and depth are paired with TUM's association rule (associate.py:
// closer than max_difference, greedy, one-to-one) — the metrics library's own implementation. Depth is
// 16-bit PNG with depth_factor units per metre (5000), registered to colour by the Kinect driver.
// Intrinsics come from the `intrinsics` option; `auto` reads camera.txt when the folder has one (as
// `vobench synth` writes), else guesses from the folder name (freiburg1/2/3) and says so in a warning.
#include "tum_cameras.hpp"  // plugins/common
#include "tum_lists.hpp"    // plugins/common

#include "metrics/association.hpp"
#include "metrics/trajectory_io.hpp"

#include "dataset_files.hpp"  // plugins/common

#include <vobench/plugin.hpp>

#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using vobench::sdk::Error;

using Intrinsics = vobench::tum::PublishedCamera;
using vobench::tum::kFr1;
using vobench::tum::kFr2;
using vobench::tum::kFr3;
using vobench::tum::kRosDefault;

class TumReader : public vobench::sdk::Dataset {
public:
    static vobench::sdk::PluginInfo info() {
        return {"tum",
                "1.0.0",
                "TUM RGB-D benchmark sequences (rgb.txt, depth.txt, groundtruth.txt; depth 1/5000 m).",
                "MIT",
                "https://cvg.cit.tum.de/data/datasets/rgbd-dataset",
                {{"intrinsics", VOBENCH_PARAM_ENUM, "auto", 0, 0, "auto|fr1|fr2|fr3|ros-default|explicit",
                  "colour camera calibration; auto guesses from the folder name (with a warning)"},
                 {"fx", VOBENCH_PARAM_DOUBLE, "525", 1, 1e5, "", "explicit intrinsics: focal length x, px"},
                 {"fy", VOBENCH_PARAM_DOUBLE, "525", 1, 1e5, "", "explicit intrinsics: focal length y, px"},
                 {"cx", VOBENCH_PARAM_DOUBLE, "319.5", -1e5, 1e5, "", "explicit intrinsics: principal point x, px"},
                 {"cy", VOBENCH_PARAM_DOUBLE, "239.5", -1e5, 1e5, "", "explicit intrinsics: principal point y, px"},
                 {"distortion", VOBENCH_PARAM_STRING, "", 0, 0, "", "explicit intrinsics: up to 8 coefficients k1 k2 p1 p2 k3 ..."},
                 {"undistort", VOBENCH_PARAM_BOOL, "false", 0, 0, "",
                  "undistort colour and depth before delivery (then plugins see no distortion)"},
                 {"depth_factor", VOBENCH_PARAM_DOUBLE, "5000", 1, 1e6, "", "depth units per metre"},
                 {"max_difference", VOBENCH_PARAM_DOUBLE, "0.02", 0.0001, 1, "",
                  "colour-depth association: largest stamp difference, seconds"}}};
    }

    void open(const std::string& path, const vobench::sdk::Params& options) override {
        root_ = path;
        if (!fs::is_directory(root_)) throw Error(VOBENCH_IO_ERROR, path + ": not a folder");
        const auto rgb = vobench::tum::parse_list(vobench::files::read_text(root_ / "rgb.txt"), (root_ / "rgb.txt").string());
        const auto depth = vobench::tum::parse_list(vobench::files::read_text(root_ / "depth.txt"), (root_ / "depth.txt").string());
        std::vector<double> rgb_stamps, depth_stamps;
        for (const auto& e : rgb) rgb_stamps.push_back(e.stamp);
        for (const auto& e : depth) depth_stamps.push_back(e.stamp);
        vobench::metrics::AssociationOptions assoc;
        assoc.max_difference = options.get_double("max_difference");
        try {
            for (const auto& m : vobench::metrics::associate(rgb_stamps, depth_stamps, assoc).matches)
                pairs_.push_back({rgb[m.first], depth[m.second]});
        } catch (const std::runtime_error& e) {
            throw Error(VOBENCH_IO_ERROR, path + ": colour and depth lists do not pair up: " + e.what());
        }

        const fs::path gt_path = root_ / "groundtruth.txt";
        if (fs::exists(gt_path)) {
            try {
                const auto gt = vobench::metrics::read_trajectory(gt_path);
                for (const std::string& w : gt.warnings) host().warn(w);
                for (const auto& p : gt.poses)
                    ground_truth_.insert(ground_truth_.end(), {p.t, p.p.x(), p.p.y(), p.p.z(), p.q.x(), p.q.y(), p.q.z(), p.q.w()});
            } catch (const vobench::metrics::TrajectoryError& e) {
                throw Error(VOBENCH_IO_ERROR, e.what());
            }
        }

        set_intrinsics(options);
        depth_factor_ = options.get_double("depth_factor");
        undistort_ = options.get_bool("undistort");
        name_ = fs::absolute(root_).lexically_normal().filename().string();
        if (name_.empty()) name_ = fs::absolute(root_).lexically_normal().parent_path().filename().string();

        // Frame geometry from the first colour image; every frame is checked against it.
        const cv::Mat first = vobench::files::load_image(root_ / pairs_.front().color.path, cv::IMREAD_UNCHANGED);
        camera_.struct_size = sizeof(camera_);
        camera_.width = first.cols;
        camera_.height = first.rows;
        if (undistort_) prepare_undistortion();

        info_.struct_size = sizeof(info_);
        info_.name = name_.c_str();
        info_.sensor = sensor_.c_str();
        info_.camera = &camera_;
        info_.depth_width = first.cols;
        info_.depth_height = first.rows;
        info_.depth_scale = 1.0 / depth_factor_;
        info_.frame_count = pairs_.size();
        info_.ground_truth = ground_truth_.empty() ? nullptr : ground_truth_.data();
        info_.gt_count = ground_truth_.size() / 8;
        // Motion capture's own error is not published per sequence.
        vobench::files::declare_gt_accuracy(info_, path);
    }

    const vobench_sequence_info& describe() override {
        if (pairs_.empty()) throw Error(VOBENCH_ERROR, "describe() before a successful open()");
        return info_;
    }

    const vobench_frame& read_frame(uint64_t index) override {
        vobench::files::require_frame_index(index, pairs_.size());
        const Pair& pair = pairs_[index];
        const fs::path color_path = root_ / pair.color.path, depth_path = root_ / pair.depth.path;
        auto images = vobench::files::load_color_and_depth(color_path, cv::IMREAD_COLOR, depth_path, cv::IMREAD_UNCHANGED);
        color_ = std::move(images.color);
        depth_ = std::move(images.depth);
        if (color_.type() != CV_8UC3) throw Error(VOBENCH_IO_ERROR, color_path.string() + ": not an 8-bit colour image");
        vobench::files::require_depth16(depth_, depth_path);
        if (color_.cols != camera_.width || color_.rows != camera_.height || depth_.size() != color_.size())
            throw Error(VOBENCH_IO_ERROR, "frame " + std::to_string(index) + ": colour " + color_path.string() + " is " +
                                              std::to_string(color_.cols) + "x" + std::to_string(color_.rows) + ", depth " +
                                              depth_path.string() + " is " + std::to_string(depth_.cols) + "x" +
                                              std::to_string(depth_.rows) + " (expected " + std::to_string(camera_.width) + "x" +
                                              std::to_string(camera_.height) + " for both)");
        if (undistort_) {
            cv::Mat c, d;
            cv::remap(color_, c, map1_, map2_, cv::INTER_LINEAR);
            cv::remap(depth_, d, map1_, map2_, cv::INTER_NEAREST);  // never blend depths across edges
            color_ = c;
            depth_ = d;
        }
        color_image_ = vobench::files::image_of(color_, VOBENCH_PIXEL_BGR8);
        depth_image_ = vobench::files::image_of(depth_, VOBENCH_PIXEL_DEPTH_U16);
        frame_ = {sizeof(vobench_frame), index, pair.color.stamp, pair.depth.stamp, &color_image_, &depth_image_, 1.0 / depth_factor_};
        return frame_;
    }

private:
    struct Pair {
        vobench::tum::ListEntry color, depth;
    };

    void set_intrinsics(const vobench::sdk::Params& options) {
        std::string which = options.get_string("intrinsics");
        if (which == "auto" && fs::exists(root_ / "camera.txt")) {
            read_camera_file(root_ / "camera.txt");
            return;
        }
        if (which == "auto") {
            const std::string folder = fs::absolute(root_).lexically_normal().string();
            which = folder.find("freiburg1") != std::string::npos   ? "fr1"
                    : folder.find("freiburg2") != std::string::npos ? "fr2"
                    : folder.find("freiburg3") != std::string::npos ? "fr3"
                                                                    : "ros-default";
            host().warn("intrinsics guessed from the folder name: " + which + " (set the option intrinsics= to be sure)");
        }
        Intrinsics in = kRosDefault;
        sensor_ = "kinect1";
        if (which == "fr1")
            in = kFr1;
        else if (which == "fr2")
            in = kFr2;
        else if (which == "fr3") {
            in = kFr3;
            sensor_ = "xtion";
        }
        camera_.fx = in.fx;
        camera_.fy = in.fy;
        camera_.cx = in.cx;
        camera_.cy = in.cy;
        camera_.distortion_count = 5;
        for (int i = 0; i < 5; ++i) camera_.distortion[i] = in.d[i];
        if (which == "explicit") {
            camera_.fx = options.get_double("fx");
            camera_.fy = options.get_double("fy");
            camera_.cx = options.get_double("cx");
            camera_.cy = options.get_double("cy");
            std::istringstream ss(options.get_string("distortion"));
            camera_.distortion_count = 0;
            double v;
            while (ss >> v) {
                if (camera_.distortion_count == 8) throw Error(VOBENCH_INVALID_ARGUMENT, "distortion: at most 8 coefficients");
                camera_.distortion[camera_.distortion_count++] = v;
            }
            if (!ss.eof()) throw Error(VOBENCH_INVALID_ARGUMENT, "distortion: not a list of numbers");
        }
        bool any = false;
        for (int i = 0; i < camera_.distortion_count; ++i) any = any || camera_.distortion[i] != 0.0;
        camera_.distortion_model = any ? VOBENCH_DISTORTION_OPENCV : VOBENCH_DISTORTION_NONE;
    }

    // camera.txt (written by `vobench synth`): one line `fx fy cx cy d0 … d7`, '#' comments.
    void read_camera_file(const fs::path& path) {
        std::istringstream in(vobench::files::read_text(path));
        std::string line;
        std::size_t number = 0;
        while (std::getline(in, line)) {
            ++number;
            if (line.empty() || line[0] == '#') continue;
            std::istringstream fields(line);
            std::vector<double> v;
            double x;
            while (fields >> x) v.push_back(x);
            if (!fields.eof() || v.size() < 4 || v.size() > 12)
                throw Error(VOBENCH_IO_ERROR,
                            path.string() + ":" + std::to_string(number) + ": expected `fx fy cx cy` and up to 8 distortion coefficients");
            camera_.fx = v[0];
            camera_.fy = v[1];
            camera_.cx = v[2];
            camera_.cy = v[3];
            camera_.distortion_count = static_cast<int32_t>(v.size() - 4);
            for (std::size_t i = 4; i < v.size(); ++i) camera_.distortion[i - 4] = v[i];
            camera_.distortion_model = v.size() > 4 ? VOBENCH_DISTORTION_OPENCV : VOBENCH_DISTORTION_NONE;
            sensor_ = "synthetic";
            // A generated sequence names its sensor model in synth.json.
            if (fs::exists(root_ / "synth.json")) {
                try {
                    sensor_ = nlohmann::json::parse(vobench::files::read_text(root_ / "synth.json")).value("sensor", sensor_);
                } catch (const nlohmann::json::exception& e) {
                    throw Error(VOBENCH_IO_ERROR, (root_ / "synth.json").string() + ": " + e.what());
                }
            }
            return;
        }
        throw Error(VOBENCH_IO_ERROR, path.string() + ": no intrinsics line");
    }

    void prepare_undistortion() {
        const cv::Matx33d K(camera_.fx, 0, camera_.cx, 0, camera_.fy, camera_.cy, 0, 0, 1);
        const cv::Mat dist(1, camera_.distortion_count, CV_64F, camera_.distortion);
        cv::initUndistortRectifyMap(K, dist, cv::noArray(), K, cv::Size(camera_.width, camera_.height), CV_32FC1, map1_, map2_);
        camera_.distortion_model = VOBENCH_DISTORTION_NONE;
        camera_.distortion_count = 0;
    }

    fs::path root_;
    std::vector<Pair> pairs_;
    std::vector<double> ground_truth_;
    std::string name_, sensor_;
    vobench_camera camera_{};
    vobench_sequence_info info_{};
    double depth_factor_ = 5000.0;
    bool undistort_ = false;
    cv::Mat map1_, map2_;
    cv::Mat color_, depth_;
    vobench_image color_image_{}, depth_image_{};
    vobench_frame frame_{};
};

}  // namespace

VOBENCH_DATASET_PLUGIN(TumReader)
