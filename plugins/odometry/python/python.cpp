// python — runs a Python class as an odometry plugin: `plugin: python, params: {module: my_vo.py}`.
// The class, its contract and the example are in this folder's README.md; the bridge itself lives in
// plugins/common/python (libvobench_python_runtime.so, shared with the python_dataset reader).
#include "python_bridges.hpp"

namespace {

class PythonOdometryPlugin : public vobench::sdk::Odometry {
public:
    static vobench::sdk::PluginInfo info() { return vobench::python::odometry_info(); }

    std::vector<vobench::sdk::Param> extra_params(const vobench::sdk::Params& given) override { return impl().extra_params(given); }
    void start(const vobench_camera& camera, const vobench::sdk::Params& params, uint64_t seed) override {
        impl().start(camera, params, seed);
    }
    vobench_tracking_status process(const vobench_frame& frame, vobench_pose& pose) override { return impl().process(frame, pose); }
    void reset() override { impl().reset(); }

private:
    // Made on the first call (the interpreter starts then, not when the host merely creates instances).
    vobench::sdk::Odometry& impl() {
        if (!impl_) impl_ = vobench::python::make_odometry(&host());
        return *impl_;
    }
    std::unique_ptr<vobench::sdk::Odometry> impl_;
};

}  // namespace

VOBENCH_ODOMETRY_PLUGIN(PythonOdometryPlugin)
