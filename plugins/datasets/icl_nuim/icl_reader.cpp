// icl_nuim — reader for ICL-NUIM (Handa et al., ICRA 2014) in its TUM-compatible layout:
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
#include "metrics/trajectory_io.hpp"

#include "dataset_files.hpp"  // plugins/common

#include <vobench/plugin.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
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
                 {"ground_truth", VOBENCH_PARAM_STRING, "", 0, 0, "", "ground-truth file (default: the folder's *.gt.freiburg)"}}};
    }

    void open(const std::string& path, const vobench::sdk::Params& o) override {
        root_ = path;
        if (!fs::is_directory(root_)) throw Error(VOBENCH_IO_ERROR, path + ": not a folder");
        rate_ = o.get_double("frame_rate");
        depth_factor_ = o.get_double("depth_factor");
        parse_associations(root_ / "associations.txt");
        const cv::Mat first = vobench::files::load_image(root_ / frames_.front().color, cv::IMREAD_COLOR);
        double k[12] = {o.get_double("fx"), o.get_double("fy"), o.get_double("cx"), o.get_double("cy")};
        int count = 4;
        if (fs::exists(root_ / "camera.txt")) count = read_camera(root_ / "camera.txt", k);
        set_camera(k, count, first.cols, first.rows);
        load_ground_truth(o.get_string("ground_truth"));
        name_ = fs::absolute(root_).lexically_normal().filename().string();
        info_ = {sizeof(info_), name_.c_str(), "icl_nuim", &camera_, first.cols, first.rows, 1.0 / depth_factor_,
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
        cv::Mat color = vobench::files::load_image(root_ / f.color, cv::IMREAD_COLOR), depth = vobench::files::load_image(root_ / f.depth, cv::IMREAD_UNCHANGED);
        vobench::files::require_depth16(depth, (root_ / f.depth));
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
        depth_image_ = vobench::files::image_of(depth_, VOBENCH_PIXEL_DEPTH_U16);
        frame_ = {sizeof(vobench_frame), index, f.stamp, f.stamp, &color_image_, &depth_image_, 1.0 / depth_factor_};
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
        try {
            const auto gt = vobench::metrics::read_trajectory(file);
            for (const std::string& w : gt.warnings) host().warn(w);
            for (const auto& p : gt.poses)
                ground_truth_.insert(ground_truth_.end(), {stamp_of(p.t), p.p.x(), p.p.y(), p.p.z(), p.q.x(), p.q.y(), p.q.z(), p.q.w()});
        } catch (const vobench::metrics::TrajectoryError& e) {
            throw Error(VOBENCH_IO_ERROR, e.what());
        }
    }

    fs::path root_;
    std::vector<Frame> frames_;
    std::vector<double> ground_truth_;
    std::string name_;
    double rate_ = 0, depth_factor_ = 5000;
    bool flip_ = false;
    vobench_camera camera_{};
    vobench_sequence_info info_{};
    cv::Mat color_, depth_;
    vobench_image color_image_{}, depth_image_{};
    vobench_frame frame_{};
};

}  // namespace

VOBENCH_DATASET_PLUGIN(IclReader)
