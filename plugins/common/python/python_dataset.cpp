// The reader bridge: a Python class with open(path, options), describe() and read_frame(i), run as a
// dataset plugin. The arrays read_frame() returns are kept (not copied, when they are contiguous and
// of a deliverable type) until the next read_frame(), as the ABI asks of any reader.
#include "python_bridges.hpp"
#include "python_runtime.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>

namespace vobench::python {
namespace {

using U8 = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>;
using F32 = py::array_t<float, py::array::c_style | py::array::forcecast>;
using U16 = py::array_t<uint16_t, py::array::c_style>;

// d[key] as T, or `fallback` when absent; a present value of the wrong type is named.
template <typename T>
T get(const py::dict& d, const char* key, const std::string& where, T fallback) {
    if (!d.contains(key) || d[key].is_none()) return fallback;
    try {
        return d[key].cast<T>();
    } catch (const py::cast_error&) {
        throw sdk::Error(VOBENCH_ERROR, where + ": '" + key + "' has the wrong type (" +
                                            py::str(py::type::handle_of(d[key]).attr("__name__")).cast<std::string>() + ")");
    }
}

template <typename T>
T need(const py::dict& d, const char* key, const std::string& where) {
    if (!d.contains(key) || d[key].is_none()) throw sdk::Error(VOBENCH_ERROR, where + " has no '" + key + "'");
    return get<T>(d, key, where, T{});
}

py::dict as_dict(const py::object& o, const std::string& where) {
    if (!py::isinstance<py::dict>(o))
        throw sdk::Error(VOBENCH_ERROR,
                         where + " must return a dict, not a " + py::str(py::type::handle_of(o).attr("__name__")).cast<std::string>());
    return o.cast<py::dict>();
}

class PythonDataset : public sdk::Dataset {
public:
    explicit PythonDataset(const sdk::Host* host) : host_(host) { ensure_interpreter(); }
    ~PythonDataset() override {
        py::gil_scoped_acquire gil;
        color_keep_ = depth_keep_ = read_ = instance_ = py::object();
        user_ = UserClass();
    }

    std::vector<sdk::Param> extra_params(const sdk::Params& given) override {
        module_ = given.get_string("module");
        class_ = given.get_string("class");
        if (module_.empty())
            throw sdk::Error(VOBENCH_INVALID_ARGUMENT, "the python_dataset reader needs module=FILE.py (or a dotted module name)");
        with_python("importing " + class_ + " from " + module_, [&] {
            HostScope scope(host_);
            user_ = load_user_class(module_, class_);
        });
        return user_.params;
    }

    void open(const std::string& path, const sdk::Params& options) override {
        with_python(class_ + ".open('" + path + "', options) in " + module_, [&] {
            HostScope scope(host_);
            instance_ = user_.cls();
            for (const char* method : {"open", "describe", "read_frame"})
                if (!py::hasattr(instance_, method))
                    throw sdk::Error(VOBENCH_ERROR, class_ + " in " + module_ + " has no " + method + "() method");
            instance_.attr("open")(path, typed_values(user_, options));
            read_ = instance_.attr("read_frame");
            take_description(as_dict(instance_.attr("describe")(), class_ + ".describe()"));
        });
    }

    const vobench_sequence_info& describe() override { return info_; }

    const vobench_frame& read_frame(uint64_t index) override {
        if (index >= info_.frame_count)
            throw sdk::Error(VOBENCH_OUT_OF_RANGE, "frame " + std::to_string(index) + " of " + std::to_string(info_.frame_count));
        const std::string where = class_ + ".read_frame(" + std::to_string(index) + ")";
        with_python(where, [&] {
            HostScope scope(host_);
            const py::dict d = as_dict(read_(index), where);
            take_frame(d, index, where);
        });
        return frame_;
    }

private:
    void take_description(const py::dict& d) {
        const std::string where = class_ + ".describe()";
        name_ = get<std::string>(d, "name", where, "sequence");
        sensor_ = get<std::string>(d, "sensor", where, "unknown");
        const py::dict cam = as_dict(need<py::object>(d, "camera", where), where + "['camera']");
        const std::string cw = where + "['camera']";
        camera_ = vobench_camera{};
        camera_.struct_size = sizeof(camera_);
        camera_.width = need<int>(cam, "width", cw);
        camera_.height = need<int>(cam, "height", cw);
        camera_.fx = need<double>(cam, "fx", cw);
        camera_.fy = need<double>(cam, "fy", cw);
        camera_.cx = need<double>(cam, "cx", cw);
        camera_.cy = need<double>(cam, "cy", cw);
        const auto distortion = get<std::vector<double>>(cam, "distortion", cw, {});
        if (distortion.size() > 8) throw sdk::Error(VOBENCH_ERROR, cw + ": at most 8 distortion coefficients (OpenCV's order)");
        camera_.distortion_model = distortion.empty() ? VOBENCH_DISTORTION_NONE : VOBENCH_DISTORTION_OPENCV;
        camera_.distortion_count = static_cast<int32_t>(distortion.size());
        for (std::size_t i = 0; i < distortion.size(); ++i) camera_.distortion[i] = distortion[i];
        const long long count = need<long long>(d, "frame_count", where);
        if (count < 0) throw sdk::Error(VOBENCH_ERROR, where + ": frame_count is negative");
        depth_scale_ = get<double>(d, "depth_scale", where, 0.0);
        gt_.clear();
        if (d.contains("ground_truth") && !d["ground_truth"].is_none()) {
            const auto gt = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(d["ground_truth"]);
            if (!gt || gt.ndim() != 2 || gt.shape(1) != 8)
                throw sdk::Error(VOBENCH_ERROR, where + ": ground_truth must be N x 8 (t tx ty tz qx qy qz qw, camera-to-world)");
            gt_.assign(gt.data(), gt.data() + gt.size());
        }
        info_ = vobench_sequence_info{};
        info_.struct_size = sizeof(info_);
        info_.name = name_.c_str();
        info_.sensor = sensor_.c_str();
        info_.camera = &camera_;
        info_.depth_width = get<int>(d, "depth_width", where, camera_.width);
        info_.depth_height = get<int>(d, "depth_height", where, camera_.height);
        info_.depth_scale = depth_scale_ > 0 ? depth_scale_ : 1.0;
        info_.frame_count = static_cast<uint64_t>(count);
        info_.ground_truth = gt_.empty() ? nullptr : gt_.data();
        info_.gt_count = gt_.size() / 8;
        info_.gt_position_sigma_m = get<double>(d, "gt_position_sigma_m", where, -1.0);
        info_.gt_rotation_sigma_deg = get<double>(d, "gt_rotation_sigma_deg", where, -1.0);
    }

    void take_frame(const py::dict& d, uint64_t index, const std::string& where) {
        const py::object rgb = need<py::object>(d, "rgb", where), depth = need<py::object>(d, "depth", where);
        const U8 color = U8::ensure(rgb);
        if (!color || !((color.ndim() == 3 && color.shape(2) == 3) || color.ndim() == 2))
            throw sdk::Error(VOBENCH_ERROR, where + ": 'rgb' must be an H x W x 3 (or H x W grey) uint8 array");
        const int w = static_cast<int>(color.shape(1)), h = static_cast<int>(color.shape(0));
        const bool grey = color.ndim() == 2;
        color_ =
            vobench_image{sizeof(vobench_image), w, h, grey ? w : 3 * w, grey ? VOBENCH_PIXEL_GRAY8 : VOBENCH_PIXEL_RGB8, color.data()};
        double scale = get<double>(d, "depth_scale", where, depth_scale_);
        py::array depth_array;
        const bool is_u16 =
            py::isinstance<py::array>(depth) && py::reinterpret_borrow<py::array>(depth).dtype().is(py::dtype::of<uint16_t>());
        if (is_u16) {
            const U16 u16 = U16::ensure(depth);  // a copy only when not C-contiguous
            if (!u16 || u16.ndim() != 2) throw sdk::Error(VOBENCH_ERROR, where + ": 'depth' must be H x W");
            if (!(scale > 0))
                throw sdk::Error(VOBENCH_ERROR, where + ": uint16 depth needs depth_scale (metres per unit) in describe() or the frame");
            depth_ = vobench_image{sizeof(vobench_image),          static_cast<int>(u16.shape(1)),
                                   static_cast<int>(u16.shape(0)), static_cast<int>(u16.shape(1)) * 2,
                                   VOBENCH_PIXEL_DEPTH_U16,        u16.data()};
            depth_array = u16;
        } else {
            const F32 f32 = F32::ensure(depth);
            if (!f32 || f32.ndim() != 2)
                throw sdk::Error(VOBENCH_ERROR, where + ": 'depth' must be an H x W float (metres) or uint16 array");
            if (!(scale > 0)) scale = 1.0;  // float depth is in metres unless said otherwise
            depth_ = vobench_image{sizeof(vobench_image),          static_cast<int>(f32.shape(1)),
                                   static_cast<int>(f32.shape(0)), static_cast<int>(f32.shape(1)) * 4,
                                   VOBENCH_PIXEL_DEPTH_F32,        f32.data()};
            depth_array = f32;
        }
        const double stamp = get<double>(d, "timestamp", where, static_cast<double>(index));
        frame_ =
            vobench_frame{sizeof(vobench_frame), index, stamp, get<double>(d, "depth_timestamp", where, stamp), &color_, &depth_, scale};
        color_keep_ = color;  // the memory the frame points to, until the next read
        depth_keep_ = depth_array;
    }

    const sdk::Host* host_;
    std::string module_, class_;
    UserClass user_;
    py::object instance_, read_, color_keep_, depth_keep_;
    std::string name_, sensor_;
    vobench_camera camera_{};
    vobench_sequence_info info_{};
    std::vector<double> gt_;
    double depth_scale_ = 0;
    vobench_image color_{}, depth_{};
    vobench_frame frame_{};
};

}  // namespace

sdk::PluginInfo dataset_info() {
    return {"python_dataset",
            "1.0.0",
            "Bridge: reads sequences with a Python class (module=FILE.py, class=Dataset: open, describe, read_frame); its "
            "PARAMS become options of this reader.",
            "MIT",
            "",
            bridge_params("Dataset", "dataset reader class"),
            true};
}

std::unique_ptr<sdk::Dataset> make_dataset(const sdk::Host* host) { return std::make_unique<PythonDataset>(host); }

}  // namespace vobench::python
