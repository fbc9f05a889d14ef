// exposure — a gain on the colour image (over- or under-exposure), with saturation at 255.
#include "filter_pixels.hpp"

#include <algorithm>

namespace {

class Exposure : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {"exposure", "1.0.0", "Multiplies the colour image by a gain (exposure change), saturating at 255.",
                "MIT",      "",      {{"gain", VOBENCH_PARAM_DOUBLE, "1.5", 0, 16, "", "factor on every colour value (1: unchanged)"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& p, uint64_t) override { gain_ = p.get_double("gain"); }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (gain_ == 1.0) return &in;
        buffer_.copy_from(in);
        const vobench_image& c = buffer_.color_image();
        uint8_t* px = buffer_.color();
        for (std::size_t i = 0; i < static_cast<std::size_t>(c.stride_bytes) * static_cast<std::size_t>(c.height); ++i)
            px[i] = static_cast<uint8_t>(std::min(255.0, std::round(px[i] * gain_)));
        return &buffer_.frame();
    }

private:
    double gain_ = 1;
    vobench::sdk::FrameBuffer buffer_;
};

}  // namespace

VOBENCH_FILTER_PLUGIN(Exposure)
