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

#include <vobench/plugin.hpp>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using vobench::sdk::Error;


class IclReader : public vobench::sdk::Dataset {
public:
    static vobench::sdk::PluginInfo info() {
        return {"icl_nuim",
                "1.0.0",
                "ICL-NUIM (Handa et al. 2014), TUM-compatible layout; images flipped so that plugins see fy > 0.",
                "MIT",
                "https://www.doc.ic.ac.uk/~ahanda/VaFRIC/iclnuim.html",
                {{"fx", VOBENCH_PARAM_DOUBLE, "481.2", -1e5, 1e5, "", "focal length x, px (ICL convention; camera.txt overrides)"},
                 {"fy", VOBENCH_PARAM_DOUBLE, "-480", -1e5, 1e5, "", "focal length y, px (ICL: negative)"},
                 {"cx", VOBENCH_PARAM_DOUBLE, "319.5", -1e5, 1e5, "", "principal point x, px"},
                 {"cy", VOBENCH_PARAM_DOUBLE, "239.5", -1e5, 1e5, "", "principal point y, px (ICL convention)"},
                 {"depth_factor", VOBENCH_PARAM_DOUBLE, "5000", 1, 1e6, "", "depth units per metre"},
                 {"frame_rate", VOBENCH_PARAM_DOUBLE, "0", 0, 1000, "", "stamps are frame / rate seconds; 0: frame indices"},
                 {"ground_truth", VOBENCH_PARAM_STRING, "", 0, 0, "",
                  "ground-truth file, *.gt.freiburg (TUM layout) or *.gt.sim (3x4 per frame); default: the folder's"},
                 {"layout", VOBENCH_PARAM_ENUM, "auto", 0, 0, "auto|icl-tum|icl-povray", "auto: associations.txt or scene_00_0000.png"},
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
        if (povray_) list_povray_frames();
        else parse_associations(root_ / "associations.txt");
        const cv::Mat first = vobench::files::load_image(root_ / frames_.front().color, cv::IMREAD_COLOR);
        double k[12] = {o.get_double("fx"), o.get_double("fy"), o.get_double("cx"), o.get_double("cy")};
        if (povray_) k[1] = std::abs(k[1]);  // poses from the camera vectors: upright images
        int count = 4;
        if (fs::exists(root_ / "camera.txt")) count = read_camera(root_ / "camera.txt", k);
        set_camera(k, count, first.cols, first.rows);
        if (povray_ && o.get_string("ground_truth").empty()) poses_from_camera_vectors();
        else load_ground_truth(o.get_string("ground_truth"));
        name_ = fs::absolute(root_).lexically_normal().filename().string();
        info_ = {sizeof(info_), name_.c_str(), "icl_nuim", &camera_, first.cols, first.rows, povray_ ? 1.0 : 1.0 / depth_factor_,
                 frames_.size(), ground_truth_.empty() ? nullptr : ground_truth_.data(), ground_truth_.size() / 8};
    }

    const vobench_sequence_info& describe() override {
        if (frames_.empty()) throw Error(VOBENCH_ERROR, "describe() before a successful open()");
        return info_;
    }

    const vobench_frame& read_frame(uint64_t index) override {
        if (index >= frames_.size())
            throw Error(VOBENCH_OUT_OF_RANGE, "frame " + std::to_string(index) + " is past the end (" + std::to_string(frames_.size()) + " frames)");
        const Frame& f = frames_[index];
        cv::Mat color = vobench::files::load_image(root_ / f.color, cv::IMREAD_COLOR);
        cv::Mat depth = povray_ ? read_ray_depth(root_ / f.depth, color.size()) : vobench::files::load_image(root_ / f.depth, cv::IMREAD_UNCHANGED);
        if (!povray_) vobench::files::require_depth16(depth, (root_ / f.depth));
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
        frame_ = {sizeof(vobench_frame), index, f.stamp, f.stamp, &color_image_, &depth_image_, povray_ ? 1.0 : 1.0 / depth_factor_};
        return frame_;
    }

private:
    struct Frame {
        double stamp;
        std::string color, depth;
    };


    double stamp_of(double index) const { return rate_ > 0 ? index / rate_ : index; }

    // associations.txt: `t_depth depth/i.png t_rgb rgb/i.png` per line.
    void parse_associations(const fs::path& path) {
        std::istringstream in(vobench::files::read_text(path));
        std::string line;
        std::size_t number = 0;
        while (std::getline(in, line)) {
            ++number;
            if (!line.empty() && line.back() == '\r') line.pop_back();
            if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
            std::istringstream fields(line);
            double t_depth, t_rgb;
            std::string depth, rgb, extra;
            if (!(fields >> t_depth >> depth >> t_rgb >> rgb) || (fields >> extra))
                throw Error(VOBENCH_IO_ERROR, path.string() + ":" + std::to_string(number) + ": expected `t_depth depth_file t_rgb rgb_file`");
            if (!frames_.empty() && stamp_of(t_rgb) <= frames_.back().stamp)
                throw Error(VOBENCH_IO_ERROR, path.string() + ":" + std::to_string(number) + ": stamps must increase");
            frames_.push_back({stamp_of(t_rgb), rgb, depth});
        }
        if (frames_.empty()) throw Error(VOBENCH_IO_ERROR, path.string() + ": no frames (empty sequence)");
    }

    static int read_camera(const fs::path& path, double* k) {
        std::istringstream in(vobench::files::read_text(path));
        std::string line;
        std::size_t number = 0;
        while (std::getline(in, line)) {
            ++number;
            if (line.empty() || line[0] == '#') continue;
            std::istringstream fields(line);
            int count = 0;
            double v;
            while (count < 12 && fields >> v) k[count++] = v;
            if (count < 4 || !(fields >> std::ws).eof())
                throw Error(VOBENCH_IO_ERROR, path.string() + ":" + std::to_string(number) + ": expected `fx fy cx cy` and up to 8 distortion coefficients");
            return count;
        }
        throw Error(VOBENCH_IO_ERROR, path.string() + ": no intrinsics line");
    }

    void list_povray_frames() {
        for (int k = 0;; ++k) {
            const std::string base = fmt::format("scene_00_{:04d}", k);
            if (!fs::exists(root_ / (base + ".png"))) break;
            frames_.push_back({stamp_of(k), base + ".png", base + ".depth"});
        }
        if (frames_.empty()) throw Error(VOBENCH_IO_ERROR, root_.string() + ": no scene_00_0000.png (empty sequence)");
    }

    // Ray distances (text) → z in metres, via each pixel's undistorted ray.
    cv::Mat read_ray_depth(const fs::path& path, cv::Size size) {
        if (ray_norm_.empty()) {
            std::vector<cv::Point2f> pixels, rays;
            for (int v = 0; v < size.height; ++v)
                for (int u = 0; u < size.width; ++u) pixels.emplace_back(static_cast<float>(u), static_cast<float>(v));
            const cv::Matx33d K(camera_.fx, 0, camera_.cx, 0, flip_ ? -camera_.fy : camera_.fy, flip_ ? (size.height - 1) - camera_.cy : camera_.cy, 0, 0, 1);
            cv::undistortPoints(pixels, rays, K, cv::Mat(1, camera_.distortion_count, CV_64F, camera_.distortion));
            ray_norm_.create(size, CV_32F);
            for (std::size_t i = 0; i < rays.size(); ++i)
                ray_norm_.at<float>(static_cast<int>(i) / size.width, static_cast<int>(i) % size.width) =
                    static_cast<float>(std::sqrt(1.0 + rays[i].x * rays[i].x + rays[i].y * rays[i].y));
        }
        const std::string text = vobench::files::read_text(path);
        cv::Mat z(size, CV_32F);
        const char* p = text.c_str();
        const int total = size.width * size.height;
        for (int i = 0; i < total; ++i) {
            char* end = nullptr;
            const double d = std::strtod(p, &end);
            if (end == p || !std::isfinite(d) || d < 0)
                throw Error(VOBENCH_IO_ERROR, path.string() + ": value " + std::to_string(i + 1) + " of " + std::to_string(total) +
                                                  (end == p ? " is missing or not a number" : " is not a non-negative finite number"));
            z.at<float>(i / size.width, i % size.width) = static_cast<float>(d * depth_unit_) / ray_norm_.at<float>(i / size.width, i % size.width);
            p = end;
        }
        while (*p == ' ' || *p == '\n' || *p == '\r' || *p == '\t') ++p;
        if (*p) throw Error(VOBENCH_IO_ERROR, path.string() + ": more than " + std::to_string(total) + " values");
        return z;
    }

    // Pose from POV-Ray camera vectors (see the header).
    void poses_from_camera_vectors() {
        for (std::size_t i = 0; i < frames_.size(); ++i) {
            const fs::path path = root_ / (frames_[i].color.substr(0, frames_[i].color.size() - 4) + ".txt");
            if (!fs::exists(path)) continue;  // a frame without a pose
            std::map<std::string, Eigen::Vector3d> vectors;
            std::istringstream in(vobench::files::read_text(path));
            std::string line;
            for (std::size_t n = 1; std::getline(in, line); ++n) {
                const auto eq = line.find('='), open = line.find('['), close = line.find(']');
                if (eq == std::string::npos) continue;
                std::string name = line.substr(0, eq);
                name.erase(name.find_last_not_of(" \t") + 1);
                if (open == std::string::npos || close == std::string::npos || close < open) continue;  // a scalar (cam_angle)
                std::istringstream values(line.substr(open + 1, close - open - 1));
                Eigen::Vector3d v;
                char comma;
                if (!(values >> v.x() >> comma >> v.y() >> comma >> v.z()))
                    throw Error(VOBENCH_IO_ERROR, path.string() + ":" + std::to_string(n) + ": expected `" + name + " = [x, y, z]';`");
                vectors[name] = v;
            }
            for (const char* needed : {"cam_pos", "cam_dir", "cam_up"})
                if (!vectors.count(needed)) throw Error(VOBENCH_IO_ERROR, path.string() + ": no " + std::string(needed));
            const Eigen::Vector3d z = vectors["cam_dir"].normalized();
            const Eigen::Vector3d up = vectors["cam_up"] - vectors["cam_up"].dot(z) * z;
            if (up.norm() < 1e-9) throw Error(VOBENCH_IO_ERROR, path.string() + ": cam_up is parallel to cam_dir");
            const Eigen::Vector3d y = -up.normalized(), x = y.cross(z);
            Eigen::Matrix3d R;
            R << x, y, z;
            const Eigen::Quaterniond q(R);
            const Eigen::Vector3d t = vectors["cam_pos"];
            ground_truth_.insert(ground_truth_.end(), {frames_[i].stamp, t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()});
        }
    }

    void set_camera(const double* k, int count, int width, int height) {
        flip_ = k[1] < 0;
        camera_.struct_size = sizeof(camera_);
        camera_.width = width;
        camera_.height = height;
        camera_.fx = k[0];
        camera_.fy = flip_ ? -k[1] : k[1];
        camera_.cx = k[2];
        camera_.cy = flip_ ? (height - 1) - k[3] : k[3];
        camera_.distortion_count = count - 4;
        for (int i = 0; i < count - 4; ++i) camera_.distortion[i] = k[4 + i];
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
                if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) file = entry.path();
            }
        }
        if (file.empty()) return;  // no ground truth: tracking still works
        if (file.extension() == ".sim") return load_sim(file);
        try {
            const auto gt = vobench::metrics::read_trajectory(file);
            for (const std::string& w : gt.warnings) host().warn(w);
            for (const auto& p : gt.poses)
                ground_truth_.insert(ground_truth_.end(), {stamp_of(p.t), p.p.x(), p.p.y(), p.p.z(), p.q.x(), p.q.y(), p.q.z(), p.q.w()});
        } catch (const vobench::metrics::TrajectoryError& e) {
            throw Error(VOBENCH_IO_ERROR, e.what());
        }
    }

    // <name>.gt.sim: per frame three lines, the rows of [R|t] (camera-to-world).
    void load_sim(const fs::path& path) {
        std::istringstream in(vobench::files::read_text(path));
        std::vector<double> v;
        std::string token;
        while (in >> token) {
            char* end = nullptr;
            v.push_back(std::strtod(token.c_str(), &end));
            if (*end != '\0' || !std::isfinite(v.back()))
                throw Error(VOBENCH_IO_ERROR, path.string() + ": value " + std::to_string(v.size()) + " ('" + token + "') is not a number");
        }
        if (v.size() % 12 != 0) throw Error(VOBENCH_IO_ERROR, path.string() + ": " + std::to_string(v.size()) + " values, not 12 per frame");
        for (std::size_t f = 0; f * 12 < v.size(); ++f) {
            Eigen::Matrix3d R;
            R << v[f * 12 + 0], v[f * 12 + 1], v[f * 12 + 2], v[f * 12 + 4], v[f * 12 + 5], v[f * 12 + 6], v[f * 12 + 8], v[f * 12 + 9], v[f * 12 + 10];
            if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-3)
                throw Error(VOBENCH_IO_ERROR, path.string() + ": frame " + std::to_string(f) + " is not a rotation");
            const Eigen::Quaterniond q = Eigen::Quaterniond(R).normalized();
            ground_truth_.insert(ground_truth_.end(), {stamp_of(static_cast<double>(f)), v[f * 12 + 3], v[f * 12 + 7], v[f * 12 + 11], q.x(), q.y(), q.z(), q.w()});
        }
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
