// template — the smallest complete vobench odometry plugin written with the C++ SDK.
// Copy this folder, rename the class and the plugin name, and put your algorithm in process().
//
// What it shows: the static info() (name, version, licence, parameter table), reading parameters in
// start(), reading the borrowed frame in process(), timing a stage and reporting a counter through
// the host, and returning a pose and a tracking status. Any exception you throw becomes an error
// status with your message; nothing crosses the C boundary.
#include <vobench/plugin.hpp>

#include <cstdint>

namespace {

class TemplateVo : public vobench::sdk::Odometry {
public:
    // What `vobench plugins info template` shows, and what configs are validated against.
    static vobench::sdk::PluginInfo info() {
        return {"template",
                "0.1.0",
                "Template plugin: measures the valid-depth ratio of each frame and reports the identity pose.",
                "MIT",
                "",
                {{"min_valid_ratio", VOBENCH_PARAM_DOUBLE, "0.05", 0.0, 1.0, "",
                  "below this fraction of valid depth pixels the frame is reported as lost"}}};
    }

    // Called once, before the first frame. Copy what you need: the camera is only borrowed.
    void start(const vobench_camera& camera, const vobench::sdk::Params& params, uint64_t /*seed*/) override {
        camera_ = camera;
        min_valid_ratio_ = params.get_double("min_valid_ratio");
    }

    // Called for every frame; the frame and its images are borrowed for this call only.
    vobench_tracking_status process(const vobench_frame& frame, vobench_pose& pose) override {
        double ratio = 0.0;
        {
            vobench::sdk::Host::Stage stage(host(), "depth_check");  // shows up in timing.csv
            const vobench_image& depth = *frame.depth;
            std::size_t valid = 0;
            for (int y = 0; y < depth.height; ++y) {
                const auto* row = reinterpret_cast<const uint8_t*>(depth.data) + static_cast<std::size_t>(y) * depth.stride_bytes;
                for (int x = 0; x < depth.width; ++x) {
                    if (depth.format == VOBENCH_PIXEL_DEPTH_U16)
                        valid += reinterpret_cast<const uint16_t*>(row)[x] != 0;
                    else
                        valid += reinterpret_cast<const float*>(row)[x] > 0.0f;
                }
            }
            ratio = static_cast<double>(valid) / (static_cast<double>(depth.width) * depth.height);
        }
        host().counter("valid_depth_ratio", ratio);
        // Your estimate goes here: camera-to-world, quaternion x y z w, metres.
        pose.tx = pose.ty = pose.tz = 0.0;
        pose.qx = pose.qy = pose.qz = 0.0;
        pose.qw = 1.0;
        return ratio >= min_valid_ratio_ ? VOBENCH_TRACKING_OK : VOBENCH_TRACKING_LOST;
    }

private:
    vobench_camera camera_{};
    double min_valid_ratio_ = 0.05;
};

}  // namespace

VOBENCH_ODOMETRY_PLUGIN(TemplateVo)
