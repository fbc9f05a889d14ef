// constant_pose — the null baseline: every frame gets the same pose (identity by default).
// The floor of every leaderboard: an algorithm that does not beat it has learnt nothing.
#include <vobench/plugin.hpp>

namespace {

class ConstantPose : public vobench::sdk::Odometry {
public:
    static vobench::sdk::PluginInfo info() {
        return {"constant_pose",
                "1.0.0",
                "Null baseline: reports the same pose (identity unless set) for every frame.",
                "MIT",
                "",
                {{"tx", VOBENCH_PARAM_DOUBLE, "0", -1e6, 1e6, "", "x of the constant position, metres"},
                 {"ty", VOBENCH_PARAM_DOUBLE, "0", -1e6, 1e6, "", "y of the constant position, metres"},
                 {"tz", VOBENCH_PARAM_DOUBLE, "0", -1e6, 1e6, "", "z of the constant position, metres"}}};
    }

    void start(const vobench_camera&, const vobench::sdk::Params& params, uint64_t) override {
        tx_ = params.get_double("tx");
        ty_ = params.get_double("ty");
        tz_ = params.get_double("tz");
    }

    vobench_tracking_status process(const vobench_frame&, vobench_pose& pose) override {
        pose.tx = tx_;
        pose.ty = ty_;
        pose.tz = tz_;
        pose.qx = pose.qy = pose.qz = 0.0;
        pose.qw = 1.0;
        return VOBENCH_TRACKING_OK;
    }

    void reset() override {}

private:
    double tx_ = 0, ty_ = 0, tz_ = 0;
};

}  // namespace

VOBENCH_ODOMETRY_PLUGIN(ConstantPose)
