// depth_quantization — rounds depth to a coarser step (a cheaper sensor, a lossy format).
#include "filter_pixels.hpp"

namespace {

class DepthQuantization : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {"depth_quantization",
                "1.0.0",
                "Rounds every depth reading to a multiple of a step in metres.",
                "MIT",
                "",
                {{"step", VOBENCH_PARAM_DOUBLE, "0.01", 0, 10, "", "quantisation step, metres (0: unchanged)"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& p, uint64_t) override { step_ = p.get_double("step"); }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (step_ <= 0) return &in;
        buffer_.copy_from(in);
        const vobench_frame& f = buffer_.frame();
        uint8_t* depth = buffer_.depth();
        for (std::size_t i = 0; i < vobench::filters::pixels(f); ++i)
            if (const double z = vobench::filters::depth_m(f, depth, i); z > 0)
                vobench::filters::set_depth_m(f, depth, i, std::max(step_, std::round(z / step_) * step_));
        return &buffer_.frame();
    }

private:
    double step_ = 0;
    vobench::sdk::FrameBuffer buffer_;
};

}  // namespace

VOBENCH_FILTER_PLUGIN(DepthQuantization)
