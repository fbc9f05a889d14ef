// counter — a test plugin with per-instance state: the pose's x is the number of frames this instance
// has processed plus the parameter `start`. Two instances must count independently.
// With throw_at >= 0, process() throws a std::runtime_error at that frame (the SDK must turn it into
// an error status with the message).
#include <vobench/plugin.hpp>

#include <stdexcept>

namespace {

class Counter : public vobench::sdk::Odometry {
public:
    static vobench::sdk::PluginInfo info() {
        return {"counter",
                "1.0.0",
                "Test plugin: counts frames per instance.",
                "MIT",
                "",
                {{"start", VOBENCH_PARAM_INT, "0", -1000, 1000, "", "first count"},
                 {"throw_at", VOBENCH_PARAM_INT, "-1", -1, 1000000, "", "frame at which process() throws (-1: never)"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& params, uint64_t) override {
        count_ = params.get_int("start");
        throw_at_ = params.get_int("throw_at");
    }
    vobench_tracking_status process(const vobench_frame& frame, vobench_pose& pose) override {
        if (static_cast<long long>(frame.index) == throw_at_)
            throw std::runtime_error("deliberate failure at frame " + std::to_string(frame.index));
        vobench::sdk::Host::Stage stage(host(), "count");
        pose.tx = static_cast<double>(++count_);
        host().counter("count", static_cast<double>(count_));
        return VOBENCH_TRACKING_OK;
    }
    void reset() override { count_ = 0; }

private:
    long long count_ = 0, throw_at_ = -1;
};

}  // namespace

VOBENCH_ODOMETRY_PLUGIN(Counter)
