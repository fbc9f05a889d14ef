// color_noise — additive Gaussian noise on every colour channel (sensor read noise), clamped to 0..255.
#include "filter_pixels.hpp"

#include <algorithm>

namespace {

class ColorNoise : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {"color_noise", "1.0.0", "Additive Gaussian noise on the colour image (grey levels), clamped.",
                "MIT",         "",      {{"sigma", VOBENCH_PARAM_DOUBLE, "4", 0, 128, "", "standard deviation in grey levels (0..255)"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& p, uint64_t seed) override {
        sigma_ = p.get_double("sigma");
        seed_ = seed;
    }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (sigma_ <= 0) return &in;
        buffer_.copy_from(in);
        const vobench_image& c = buffer_.color_image();
        const std::size_t n = static_cast<std::size_t>(c.stride_bytes) * static_cast<std::size_t>(c.height);
        uint8_t* px = buffer_.color();
        auto rng = vobench::filters::frame_rng(seed_, in.index);
        std::normal_distribution<double> noise(0.0, sigma_);
        for (std::size_t i = 0; i < n; ++i) px[i] = static_cast<uint8_t>(std::clamp(std::lround(px[i] + noise(rng)), 0L, 255L));
        return &buffer_.frame();
    }

private:
    double sigma_ = 0;
    uint64_t seed_ = 0;
    vobench::sdk::FrameBuffer buffer_;
};

}  // namespace

VOBENCH_FILTER_PLUGIN(ColorNoise)
