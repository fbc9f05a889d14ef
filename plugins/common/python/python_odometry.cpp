// The odometry bridge: a Python class with process(frame) -> (pose, status), run as a plugin.
//
// Frames reach Python without a copy: frame.rgb / frame.bgr (when the reader delivers that order) and
// frame.depth_raw are read-only NumPy views of the host's buffers, valid during the call only (a view
// kept past it is refused, named, since its memory is gone); frame.depth (float32 metres, NaN where
// there is no reading) is converted on first use into an array Python owns. What the bridge itself
// costs per frame (taking the GIL, wrapping, converting, parsing the result) is measured and recorded
// as the counter python_bridge_ms, apart from the time inside the user's process().
#include "python_bridges.hpp"
#include "python_runtime.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <limits>

namespace vobench::python {
namespace {

using Clock = std::chrono::steady_clock;
double ms_between(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

// The array shares memory and cannot be written through.
py::array read_only(py::array a) {
    a.attr("flags").attr("writeable") = false;
    return a;
}

// A handle that owns nothing: the base of views of host memory (so NumPy does not copy).
py::handle no_owner() {
    static py::capsule* base = new py::capsule(reinterpret_cast<void*>(1), [](void*) {});
    return *base;
}

// What process() receives. Each image property is made on first access and kept for the call.
class FrameView {
public:
    explicit FrameView(const vobench_frame* f) : frame_(f) {}

    uint64_t index() const { return live().index; }
    double timestamp() const { return live().timestamp; }
    double depth_timestamp() const { return live().depth_timestamp; }
    double depth_scale() const { return live().depth_scale; }

    py::object rgb() { return color(true); }
    py::object bgr() { return color(false); }
    py::object depth_raw() {
        if (!depth_raw_) {
            const vobench_image& im = *live().depth;
            const bool u16 = im.format == VOBENCH_PIXEL_DEPTH_U16;
            depth_raw_ = read_only(py::array(u16 ? py::dtype::of<uint16_t>() : py::dtype::of<float>(), {im.height, im.width},
                                             {static_cast<py::ssize_t>(im.stride_bytes), static_cast<py::ssize_t>(u16 ? 2 : 4)}, im.data,
                                             no_owner()));
        }
        return depth_raw_;
    }
    py::object depth() {
        if (!depth_) {
            const auto t0 = Clock::now();
            const vobench_frame& f = live();
            const vobench_image& im = *f.depth;
            py::array_t<float> out({im.height, im.width});
            float* dst = out.mutable_data();
            const float none = std::numeric_limits<float>::quiet_NaN();
            const auto scale = static_cast<float>(f.depth_scale);
            for (int y = 0; y < im.height; ++y) {
                const char* row = static_cast<const char*>(im.data) + static_cast<std::ptrdiff_t>(y) * im.stride_bytes;
                float* o = dst + static_cast<std::ptrdiff_t>(y) * im.width;
                if (im.format == VOBENCH_PIXEL_DEPTH_U16) {
                    const auto* in = reinterpret_cast<const uint16_t*>(row);
                    for (int x = 0; x < im.width; ++x) o[x] = in[x] == 0 ? none : static_cast<float>(in[x]) * scale;
                } else {
                    const auto* in = reinterpret_cast<const float*>(row);
                    for (int x = 0; x < im.width; ++x) o[x] = (in[x] > 0 && std::isfinite(in[x])) ? in[x] * scale : none;
                }
            }
            depth_ = out;
            convert_ms_ += ms_between(t0, Clock::now());
        }
        return depth_;
    }

    // Ends the call: the images are released, and a view of host memory still referenced elsewhere is
    // named (its memory is about to be reused).
    std::string expire() {
        expired_ = true;
        std::string kept;
        const auto check = [&](py::object& view, const char* name) {
            if (view && view.ref_count() > 1 && kept.empty()) kept = name;
            view = py::object();
        };
        if (rgb_is_view_) check(rgb_, "rgb");
        if (bgr_is_view_) check(bgr_, "bgr");
        rgb_ = bgr_ = py::object();
        check(depth_raw_, "depth_raw");
        depth_ = py::object();
        return kept;
    }
    double convert_ms() const { return convert_ms_; }

private:
    const vobench_frame& live() const {
        if (expired_)
            throw std::runtime_error(
                "this frame's process() call has returned and its images are gone: copy what you keep "
                "(e.g. frame.rgb.copy())");
        return *frame_;
    }
    // rgb (want_rgb) or bgr: a view when the reader delivers that order, else a converted copy.
    py::object color(bool want_rgb) {
        py::object& cached = want_rgb ? rgb_ : bgr_;
        if (cached) return cached;
        const auto t0 = Clock::now();
        const vobench_image& im = *live().color;
        if ((want_rgb && im.format == VOBENCH_PIXEL_RGB8) || (!want_rgb && im.format == VOBENCH_PIXEL_BGR8)) {
            cached = read_only(py::array(py::dtype::of<uint8_t>(), {im.height, im.width, 3},
                                         {static_cast<py::ssize_t>(im.stride_bytes), py::ssize_t{3}, py::ssize_t{1}}, im.data, no_owner()));
            (want_rgb ? rgb_is_view_ : bgr_is_view_) = true;
            return cached;
        }
        py::array_t<uint8_t> out({im.height, im.width, 3});
        uint8_t* dst = out.mutable_data();
        for (int y = 0; y < im.height; ++y) {
            const auto* in = static_cast<const uint8_t*>(im.data) + static_cast<std::ptrdiff_t>(y) * im.stride_bytes;
            uint8_t* o = dst + static_cast<std::ptrdiff_t>(y) * im.width * 3;
            for (int x = 0; x < im.width; ++x) {
                if (im.format == VOBENCH_PIXEL_GRAY8) {
                    o[3 * x] = o[3 * x + 1] = o[3 * x + 2] = in[x];
                } else {  // the other order of three channels
                    o[3 * x] = in[3 * x + 2];
                    o[3 * x + 1] = in[3 * x + 1];
                    o[3 * x + 2] = in[3 * x];
                }
            }
        }
        cached = read_only(out);
        convert_ms_ += ms_between(t0, Clock::now());
        return cached;
    }

    const vobench_frame* frame_;
    bool expired_ = false;
    py::object rgb_, bgr_, depth_raw_, depth_;
    bool rgb_is_view_ = false, bgr_is_view_ = false;
    double convert_ms_ = 0;
};

void register_frame_type() {
    static bool done = false;  // GIL held
    if (done) return;
    py::class_<FrameView>(py::module_::import("vobench"), "Frame", "One RGB-D frame, valid during process() only")
        .def_property_readonly("index", &FrameView::index)
        .def_property_readonly("timestamp", &FrameView::timestamp, "colour stamp, seconds")
        .def_property_readonly("depth_timestamp", &FrameView::depth_timestamp, "stamp of the depth image, seconds")
        .def_property_readonly("depth_scale", &FrameView::depth_scale, "metres per unit of depth_raw")
        .def_property_readonly("rgb", &FrameView::rgb, "H x W x 3 uint8, R G B (read-only; a view when the reader delivers RGB)")
        .def_property_readonly("bgr", &FrameView::bgr, "H x W x 3 uint8, B G R, OpenCV's order (read-only; a view when delivered so)")
        .def_property_readonly("depth", &FrameView::depth, "H x W float32 metres, NaN where there is no reading")
        .def_property_readonly("depth_raw", &FrameView::depth_raw, "H x W as delivered (uint16 or float32) x depth_scale = metres; a view");
    done = true;
}

// A double array of `shape` from any sequence or array; NULL-object when it is not one.
py::array_t<double> as_doubles(const py::handle& obj) {
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
}

std::string type_of(const py::handle& obj) { return py::str(py::type::handle_of(obj).attr("__name__")).cast<std::string>(); }

// (pose, status) as process() returned it → the ABI's pose and status, or the reason it is not one.
vobench_tracking_status read_result(const py::object& result, vobench_pose& pose) {
    if (!(py::isinstance<py::tuple>(result) || py::isinstance<py::list>(result)) || py::len(result) != 2)
        throw sdk::Error(VOBENCH_ERROR, "process() must return (pose, status), it returned a " + type_of(result) +
                                            (py::isinstance<py::tuple>(result) ? " of " + std::to_string(py::len(result)) : ""));
    const py::object pose_obj = result[py::int_(0)], status_obj = result[py::int_(1)];
    vobench_tracking_status status;
    if (!py::isinstance<py::str>(status_obj))
        throw sdk::Error(VOBENCH_ERROR, "process(): the status must be 'ok', 'lost' or 'failed', not a " + type_of(status_obj));
    const std::string word = status_obj.cast<std::string>();
    if (word == "ok")
        status = VOBENCH_TRACKING_OK;
    else if (word == "lost")
        status = VOBENCH_TRACKING_LOST;
    else if (word == "failed")
        status = VOBENCH_TRACKING_FAILED;
    else
        throw sdk::Error(VOBENCH_ERROR, "process(): the status must be 'ok', 'lost' or 'failed', not '" + word + "'");

    Eigen::Vector3d t;
    Eigen::Quaterniond q;
    const bool pair = (py::isinstance<py::tuple>(pose_obj) || py::isinstance<py::list>(pose_obj)) && py::len(pose_obj) == 2;
    if (pair) {  // (t, q): t = x y z in metres, q = x y z w
        const py::array_t<double> ta = as_doubles(pose_obj[py::int_(0)]), qa = as_doubles(pose_obj[py::int_(1)]);
        if (!ta || !qa || ta.size() != 3 || qa.size() != 4)
            throw sdk::Error(VOBENCH_ERROR, "process(): a pose (t, q) needs 3 numbers in t and 4 in q (x, y, z, w)");
        t = Eigen::Vector3d(ta.data()[0], ta.data()[1], ta.data()[2]);
        q = Eigen::Quaterniond(qa.data()[3], qa.data()[0], qa.data()[1], qa.data()[2]);
    } else {
        const py::array_t<double> m = as_doubles(pose_obj);
        if (!m || m.ndim() != 2 || !((m.shape(0) == 4 || m.shape(0) == 3) && m.shape(1) == 4))
            throw sdk::Error(VOBENCH_ERROR,
                             "process(): the pose must be a 4x4 (or 3x4) camera-to-world matrix or (t, q), not " +
                                 (m ? "an array of shape " + py::str(m.attr("shape")).cast<std::string>() : "a " + type_of(pose_obj)));
        Eigen::Matrix<double, 3, 4, Eigen::RowMajor> rt = Eigen::Map<const Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>(m.data());
        if (!rt.allFinite()) throw sdk::Error(VOBENCH_ERROR, "process(): the pose matrix has a non-finite entry");
        if (m.shape(0) == 4) {
            const double* last = m.data() + 12;
            if (std::abs(last[0]) > 1e-9 || std::abs(last[1]) > 1e-9 || std::abs(last[2]) > 1e-9 || std::abs(last[3] - 1) > 1e-9)
                throw sdk::Error(VOBENCH_ERROR, "process(): the pose matrix's last row is not 0 0 0 1");
        }
        const Eigen::Matrix3d r = rt.leftCols<3>();
        const double off = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
        if (off > 1e-6 || r.determinant() < 0)
            throw sdk::Error(VOBENCH_ERROR, "process(): the pose's rotation is not a rotation (|R^T R - I| = " + std::to_string(off) +
                                                ", det " + std::to_string(r.determinant()) + ")");
        t = rt.col(3);
        q = Eigen::Quaterniond(r);
    }
    pose.tx = t.x();
    pose.ty = t.y();
    pose.tz = t.z();
    pose.qx = q.x();
    pose.qy = q.y();
    pose.qz = q.z();
    pose.qw = q.w();  // the host checks finiteness and unit norm
    return status;
}

class PythonOdometry : public sdk::Odometry {
public:
    explicit PythonOdometry(const sdk::Host* host) : host_(host) { ensure_interpreter(); }
    ~PythonOdometry() override {
        py::gil_scoped_acquire gil;
        process_ = py::object();
        reset_ = py::object();
        instance_ = py::object();
        user_ = UserClass();
    }

    std::vector<sdk::Param> extra_params(const sdk::Params& given) override {
        module_ = given.get_string("module");
        class_ = given.get_string("class");
        if (module_.empty()) throw sdk::Error(VOBENCH_INVALID_ARGUMENT, "the python plugin needs module=FILE.py (or a dotted module name)");
        const auto t0 = Clock::now();
        with_python("importing " + class_ + " from " + module_, [&] {
            HostScope scope(host_);
            user_ = load_user_class(module_, class_);
            register_frame_type();
        });
        import_ms_ = ms_between(t0, Clock::now());
        return user_.params;
    }

    void start(const vobench_camera& c, const sdk::Params& params, uint64_t seed) override {
        const auto t0 = Clock::now();
        with_python(class_ + "(camera, params, seed) in " + module_, [&] {
            HostScope scope(host_);
            const char* model = c.distortion_model == VOBENCH_DISTORTION_OPENCV ? "opencv" : "none";
            std::vector<double> distortion(c.distortion, c.distortion + std::max(0, std::min(8, c.distortion_count)));
            const py::object camera = helpers().attr("camera")(c.width, c.height, c.fx, c.fy, c.cx, c.cy, model, distortion);
            instance_ = user_.cls(camera, typed_values(user_, params), seed);
            if (!py::hasattr(instance_, "process"))
                throw sdk::Error(VOBENCH_ERROR, class_ + " in " + module_ + " has no process(frame) method");
            process_ = instance_.attr("process");
            if (py::hasattr(instance_, "reset")) reset_ = instance_.attr("reset");
        });
        // The first-call costs, outside every timed window, in the run log.
        host_->info("python: " + class_ + " from " + module_ + " imported in " + std::to_string(import_ms_) + " ms, constructed in " +
                    std::to_string(ms_between(t0, Clock::now())) + " ms");
    }

    vobench_tracking_status process(const vobench_frame& frame, vobench_pose& pose) override {
        const auto t0 = Clock::now();
        py::gil_scoped_acquire gil;
        HostScope scope(host_);
        py::object view = py::cast(FrameView(&frame), py::return_value_policy::move);
        FrameView& fv = view.cast<FrameView&>();
        const auto t1 = Clock::now();
        py::object result;
        try {
            result = process_(view);
        } catch (py::error_already_set& e) {
            fv.expire();
            throw sdk::Error(VOBENCH_ERROR, "frame " + std::to_string(frame.index) + ": process() raised:\n" + describe(e));
        }
        const auto t2 = Clock::now();
        const std::string kept = fv.expire();
        if (!kept.empty())
            throw sdk::Error(VOBENCH_ERROR, "frame " + std::to_string(frame.index) + ": process() kept frame." + kept +
                                                " after returning, but it is a view of the host's memory, valid during the call only: "
                                                "keep a copy (frame." +
                                                kept + ".copy())");
        vobench_tracking_status status;
        try {
            status = read_result(result, pose);
        } catch (const sdk::Error& e) {
            throw sdk::Error(e.status(), "frame " + std::to_string(frame.index) + ": " + e.what());
        } catch (py::error_already_set& e) {
            throw sdk::Error(VOBENCH_ERROR, "frame " + std::to_string(frame.index) + ": reading what process() returned:\n" + describe(e));
        }
        result = py::object();
        const double overhead = ms_between(t0, t1) + ms_between(t2, Clock::now()) + fv.convert_ms();
        host_->counter("python_bridge_ms", overhead);
        return status;
    }

    void reset() override {
        if (!reset_) throw sdk::Error(VOBENCH_UNSUPPORTED, class_ + " has no reset() method");
        with_python(class_ + ".reset()", [&] {
            HostScope scope(host_);
            reset_();
        });
    }

private:
    const sdk::Host* host_;
    std::string module_, class_;
    UserClass user_;
    py::object instance_, process_, reset_;
    double import_ms_ = 0;
};

}  // namespace

sdk::PluginInfo odometry_info() {
    sdk::PluginInfo info{"python",
                         "1.0.0",
                         "Bridge: runs a Python class (module=FILE.py, class=Odometry) as an odometry plugin; its PARAMS "
                         "become parameters of this plugin.",
                         "MIT",
                         "",
                         bridge_params("Odometry", "odometry class"),
                         true};
    return info;
}

std::unique_ptr<sdk::Odometry> make_odometry(const sdk::Host* host) { return std::make_unique<PythonOdometry>(host); }

}  // namespace vobench::python
