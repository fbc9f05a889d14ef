// icl_nuim — reader for ICL-NUIM (Handa et al., ICRA 2014), both published layouts.
//
// TUM-compatible layout (`icl-tum`):
// rgb/<i>.png, depth/<i>.png (16-bit, 5000 units per metre), associations.txt (`i depth/i.png i rgb/i.png`:
// frame indices as stamps) and <name>.gt.freiburg (TUM layout, frame indices as stamps). Frames whose
// pose is missing from the ground truth are delivered all the same; evaluation leaves them unmatched.
//
// The negative focal length. ICL-NUIM's intrinsics are fx = 481.20, fy = −480.00, cx = 319.5,
// cy = 239.5: its images are stored with y growing upwards relative to its camera frame. Plugins are
// always given fy > 0: the reader flips every image upside down and presents fy' = |fy|,
// cy' = (height − 1) − cy (and negates the tangential coefficient p1, the one odd in y). The camera
// frame, and so every ground-truth pose, stays exactly as ICL-NUIM defines it. A folder may carry a
// camera.txt (`fx fy cx cy [k1 k2 p1 p2 …]`, ICL's sign convention) that `vobench synth` writes.
//
// POV-Ray layout (`icl-povray`), frame k: scene_00_kkkk.png; scene_00_kkkk.depth, text, row by row, the
// distance along each pixel's ray from the camera centre (`depth_unit` metres), turned into
// z = d / ‖(x', y', 1)‖ with (x', y') the pixel's undistorted normalised coordinates; scene_00_kkkk.txt,
// POV-Ray camera vectors `name = [x, y, z]';` — cam_pos, cam_dir (the optical axis) and cam_up (towards
// the top of the image) — giving the pose R = [y × z, −up⊥, dir], t = cam_pos. With these poses the
// images are upright: fy > 0 (the default |fy|). A <name>.gt.sim (3×4 [R|t] per frame) is read
// instead with ground_truth=FILE. Implemented from the published description of the layout; real
// ICL-NUIM POV-Ray files were not available to check the conventions against.
#include "metrics/trajectory_io.hpp"

#include "dataset_files.hpp"  // plugins/common
#include "icl_files.hpp"

#include "metrics/trajectory_io.hpp"

#include <vobench/plugin.hpp>

#include <fmt/format.h>
#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <filesystem>

namespace {

namespace fs = std::filesystem;
using vobench::sdk::Error;

class IclReader : public vobench::sdk::Dataset {
public:
    static vobench::sdk::PluginInfo info() {
        return {"icl_nuim",
                "1.0.0",
                "ICL-NUIM (Handa et al. 2014), TUM-compatible and POV-Ray layouts; images flipped where needed so plugins see fy > 0.",
                "MIT",
                "https://www.doc.ic.ac.uk/~ahanda/VaFRIC/iclnuim.html",
                {{"fx", VOBENCH_PARAM_DOUBLE, "481.2", -1e5, 1e5, "", "focal length x, px (ICL convention; camera.txt overrides)"},
                 {"fy", VOBENCH_PARAM_DOUBLE, "-480", -1e5, 1e5, "", "focal length y, px (ICL: negative)"},
                 {"cx", VOBENCH_PARAM_DOUBLE, "319.5", -1e5, 1e5, "", "principal point x, px"},
                 {"cy", VOBENCH_PARAM_DOUBLE, "239.5", -1e5, 1e5, "", "principal point y, px (ICL convention)"},
                 {"depth_factor", VOBENCH_PARAM_DOUBLE, "5000", 1, 1e6, "", "icl-tum: depth units per metre"},
                 {"frame_rate", VOBENCH_PARAM_DOUBLE, "0", 0, 1000, "", "stamps are frame / rate seconds; 0: frame indices"},
                 {"ground_truth", VOBENCH_PARAM_STRING, "", 0, 0, "",
                  "ground-truth file, *.gt.freiburg (TUM layout) or *.gt.sim (3x4 per frame); default: the folder's"},
                 {"layout", VOBENCH_PARAM_ENUM, "auto", 0, 0, "auto|icl-tum|icl-povray", "auto: scene_00_0000.png or associations.txt"},
                 {"depth_unit", VOBENCH_PARAM_DOUBLE, "1", 1e-6, 1e3, "", "icl-povray: metres per unit of the .depth files"}}};
    }

    void open(const std::string& path, const vobench::sdk::Params& o) override {
        root_ = path;
        if (!fs::is_directory(root_)) throw Error(VOBENCH_IO_ERROR, path + ": not a folder");
        rate_ = o.get_double("frame_rate");
        depth_factor_ = o.get_double("depth_factor");
        depth_unit_ = o.get_double("depth_unit");
        std::string layout = o.get_string("layout");
        if (layout == "auto") layout = fs::exists(root_ / "scene_00_0000.png") ? "icl-povray" : "icl-tum";
        povray_ = layout == "icl-povray";
        if (povray_) {
            list_povray_frames();
        } else {
            const fs::path list = root_ / "associations.txt";
            for (const auto& a :
                 vobench::files::parsed([&] { return vobench::icl::parse_associations(vobench::files::read_text(list), list.string()); }))
                frames_.push_back({stamp_of(a.t_rgb), a.rgb, a.depth});
        }
        const cv::Mat first = vobench::files::load_image(root_ / frames_.front().color, cv::IMREAD_COLOR);
        std::vector<double> k = {o.get_double("fx"), o.get_double("fy"), o.get_double("cx"), o.get_double("cy")};
        if (povray_) k[1] = std::abs(k[1]);  // poses from the camera vectors: upright images
        if (fs::exists(root_ / "camera.txt"))
            k = vobench::files::parsed([&] {
                return vobench::icl::parse_camera(vobench::files::read_text(root_ / "camera.txt"), (root_ / "camera.txt").string());
            });
        set_camera(k, first.cols, first.rows);
        if (povray_ && o.get_string("ground_truth").empty())
            poses_from_camera_vectors();
        else
            load_ground_truth(o.get_string("ground_truth"));
        name_ = fs::absolute(root_).lexically_normal().filename().string();
        info_ = {sizeof(info_),
                 name_.c_str(),
                 "icl_nuim",
                 &camera_,
                 first.cols,
                 first.rows,
                 depth_scale(),
                 frames_.size(),
                 ground_truth_.empty() ? nullptr : ground_truth_.data(),
                 ground_truth_.size() / 8,
                 0.0,
                 0.0};  // rendered by POV-Ray: the poses are exact
    }

    const vobench_sequence_info& describe() override {
        if (frames_.empty()) throw Error(VOBENCH_ERROR, "describe() before a successful open()");
        return info_;
    }

    const vobench_frame& read_frame(uint64_t index) override {
        vobench::files::require_frame_index(index, frames_.size());
        const Frame& f = frames_[index];
        const cv::Mat color = vobench::files::load_image(root_ / f.color, cv::IMREAD_COLOR);
        const cv::Mat depth =
            povray_ ? ray_depth(root_ / f.depth, color.size()) : vobench::files::load_image(root_ / f.depth, cv::IMREAD_UNCHANGED);
        if (!povray_) vobench::files::require_depth16(depth, root_ / f.depth);
        if (color.cols != camera_.width || color.rows != camera_.height || depth.size() != color.size())
            throw Error(VOBENCH_IO_ERROR, "frame " + std::to_string(index) + ": colour " + (root_ / f.color).string() + " is " +
                                              std::to_string(color.cols) + "x" + std::to_string(color.rows) + ", depth is " +
                                              std::to_string(depth.cols) + "x" + std::to_string(depth.rows) + " (expected " +
                                              std::to_string(camera_.width) + "x" + std::to_string(camera_.height) + ")");
        if (flip_) {  // see the header: plugins see fy > 0
            cv::flip(color, color_, 0);
            cv::flip(depth, depth_, 0);
        } else {
            color_ = color;
            depth_ = depth;
        }
        color_image_ = vobench::files::image_of(color_, VOBENCH_PIXEL_BGR8);
        depth_image_ = vobench::files::image_of(depth_, povray_ ? VOBENCH_PIXEL_DEPTH_F32 : VOBENCH_PIXEL_DEPTH_U16);
        frame_ = {sizeof(vobench_frame), index, f.stamp, f.stamp, &color_image_, &depth_image_, depth_scale()};
        return frame_;
    }

private:
    struct Frame {
        double stamp;
        std::string color, depth;
    };

    double stamp_of(double index) const { return rate_ > 0 ? index / rate_ : index; }
    double depth_scale() const { return povray_ ? 1.0 : 1.0 / depth_factor_; }

    void list_povray_frames() {
        for (int k = 0;; ++k) {
            const std::string base = fmt::format("scene_00_{:04d}", k);
            if (!fs::exists(root_ / (base + ".png"))) break;
            frames_.push_back({stamp_of(k), base + ".png", base + ".depth"});
        }
        if (frames_.empty()) throw Error(VOBENCH_IO_ERROR, root_.string() + ": no scene_00_0000.png (empty sequence)");
    }

    // Ray distances → z in metres, through each pixel's undistorted ray (stored-image geometry).
    cv::Mat ray_depth(const fs::path& path, cv::Size size) {
        if (ray_norm_.empty()) {
            std::vector<cv::Point2f> pixels, rays;
            for (int v = 0; v < size.height; ++v)
                for (int u = 0; u < size.width; ++u) pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
            const cv::Matx33d K(camera_.fx, 0, camera_.cx, 0, flip_ ? -camera_.fy : camera_.fy,
                                flip_ ? (size.height - 1) - camera_.cy : camera_.cy, 0, 0, 1);
            cv::undistortPoints(pixels, rays, K, cv::Mat(1, camera_.distortion_count, CV_64F, camera_.distortion));
            ray_norm_.create(size, CV_32F);
            for (std::size_t i = 0; i < rays.size(); ++i)
                ray_norm_.at<float>(static_cast<int>(i) / size.width, static_cast<int>(i) % size.width) =
                    static_cast<float>(std::sqrt(1.0 + rays[i].x * rays[i].x + rays[i].y * rays[i].y));
        }
        const std::vector<float> d = vobench::files::parsed([&] {
            return vobench::icl::parse_ray_depth(vobench::files::read_text(path), path.string(), static_cast<std::size_t>(size.area()));
        });
        cv::Mat z(size, CV_32F);
        for (int i = 0; i < size.area(); ++i)
            z.at<float>(i / size.width, i % size.width) =
                static_cast<float>(d[static_cast<std::size_t>(i)] * depth_unit_) / ray_norm_.at<float>(i / size.width, i % size.width);
        return z;
    }

    // POV-Ray camera vectors: z = cam_dir, y = −(cam_up ⊥ z) (image y grows downwards), x = y × z.
    void poses_from_camera_vectors() {
        for (const Frame& f : frames_) {
            const fs::path path = root_ / (f.color.substr(0, f.color.size() - 4) + ".txt");
            if (!fs::exists(path)) continue;  // a frame without a pose
            auto v =
                vobench::files::parsed([&] { return vobench::icl::parse_camera_vectors(vobench::files::read_text(path), path.string()); });
            for (const char* needed : {"cam_pos", "cam_dir", "cam_up"})
                if (!v.count(needed)) throw Error(VOBENCH_IO_ERROR, path.string() + ": no " + std::string(needed));
            const Eigen::Vector3d z = v["cam_dir"].normalized();
            const Eigen::Vector3d up = v["cam_up"] - v["cam_up"].dot(z) * z;
            if (!(up.norm() > 1e-9) || !z.allFinite())
                throw Error(VOBENCH_IO_ERROR, path.string() + ": cam_up is parallel to cam_dir (or zero)");
            const Eigen::Vector3d y = -up.normalized(), x = y.cross(z);
            Eigen::Matrix3d R;
            R << x, y, z;
            add_pose(f.stamp, v["cam_pos"], Eigen::Quaterniond(R));
        }
    }

    void set_camera(const std::vector<double>& k, int width, int height) {
        flip_ = k[1] < 0;
        camera_.struct_size = sizeof(camera_);
        camera_.width = width;
        camera_.height = height;
        camera_.fx = k[0];
        camera_.fy = flip_ ? -k[1] : k[1];
        camera_.cx = k[2];
        camera_.cy = flip_ ? (height - 1) - k[3] : k[3];
        camera_.distortion_count = static_cast<int32_t>(k.size() - 4);
        for (std::size_t i = 4; i < k.size(); ++i) camera_.distortion[i - 4] = k[i];
        if (flip_ && camera_.distortion_count > 2) camera_.distortion[2] = -camera_.distortion[2];  // p1 is odd in y
        bool any = false;
        for (int i = 0; i < camera_.distortion_count; ++i) any = any || camera_.distortion[i] != 0;
        camera_.distortion_model = any ? VOBENCH_DISTORTION_OPENCV : VOBENCH_DISTORTION_NONE;
    }

    void load_ground_truth(const std::string& option) {
        fs::path file = option;
        if (file.empty()) {
            const std::string suffix = ".gt.freiburg";
            for (const auto& entry : fs::directory_iterator(root_)) {
                const std::string name = entry.path().filename().string();
                if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
                    file = entry.path();
            }
        }
        if (file.empty()) return;  // no ground truth: tracking still works
        if (file.extension() == ".sim") {
            const auto poses =
                vobench::files::parsed([&] { return vobench::icl::parse_sim(vobench::files::read_text(file), file.string()); });
            for (std::size_t i = 0; i < poses.size(); ++i)
                add_pose(stamp_of(static_cast<double>(i)), poses[i].translation(), Eigen::Quaterniond(poses[i].linear()));
            return;
        }
        try {
            const auto gt = vobench::metrics::read_trajectory(file);
            for (const std::string& w : gt.warnings) host().warn(w);
            for (const auto& p : gt.poses) add_pose(stamp_of(p.t), p.p, p.q);
        } catch (const vobench::metrics::TrajectoryError& e) {
            throw Error(VOBENCH_IO_ERROR, e.what());
        }
    }

    void add_pose(double t, const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
        ground_truth_.insert(ground_truth_.end(), {t, p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()});
    }

    fs::path root_;
    std::vector<Frame> frames_;
    std::vector<double> ground_truth_;
    std::string name_;
    double rate_ = 0, depth_factor_ = 5000, depth_unit_ = 1;
    bool flip_ = false, povray_ = false;
    cv::Mat ray_norm_;  // icl-povray: ‖(x', y', 1)‖ per pixel
    vobench_camera camera_{};
    vobench_sequence_info info_{};
    cv::Mat color_, depth_;
    vobench_image color_image_{}, depth_image_{};
    vobench_frame frame_{};
};

}  // namespace

VOBENCH_DATASET_PLUGIN(IclReader)
