// motion_blur — linear motion blur of the colour image: each pixel the mean of `length` samples along a
// line at `angle` (a camera moving during the exposure). Depth is left as it is.
#include "filter_pixels.hpp"

#include <algorithm>
#include <vector>

namespace {

class MotionBlur : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {"motion_blur",
                "1.0.0",
                "Linear motion blur of the colour image: the mean of `length` pixels along a direction.",
                "MIT",
                "",
                {{"length", VOBENCH_PARAM_INT, "9", 1, 101, "", "blur length in pixels (1: unchanged)"},
                 {"angle", VOBENCH_PARAM_DOUBLE, "0", -360, 360, "", "direction of the motion, degrees from the image x axis"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& p, uint64_t) override {
        length_ = static_cast<int>(p.get_int("length"));
        const double a = p.get_double("angle") * 3.14159265358979323846 / 180.0;
        dx_ = std::cos(a);
        dy_ = std::sin(a);
    }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (length_ <= 1) return &in;
        buffer_.copy_from(in);
        const vobench_image& c = buffer_.color_image();
        const int w = c.width, h = c.height, ch = c.format == VOBENCH_PIXEL_GRAY8 ? 1 : 3;
        const std::vector<uint8_t> src(buffer_.color(), buffer_.color() + static_cast<std::size_t>(w) * h * ch);
        uint8_t* dst = buffer_.color();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int k = 0; k < ch; ++k) {
                    int sum = 0;
                    for (int s = 0; s < length_; ++s) {
                        const double t = s - (length_ - 1) / 2.0;
                        const int sx = std::clamp(static_cast<int>(std::lround(x + t * dx_)), 0, w - 1);
                        const int sy = std::clamp(static_cast<int>(std::lround(y + t * dy_)), 0, h - 1);
                        sum += src[(static_cast<std::size_t>(sy) * w + sx) * ch + k];
                    }
                    dst[(static_cast<std::size_t>(y) * w + x) * ch + k] = static_cast<uint8_t>((sum + length_ / 2) / length_);
                }
        return &buffer_.frame();
    }

private:
    int length_ = 1;
    double dx_ = 1, dy_ = 0;
    vobench::sdk::FrameBuffer buffer_;
};

}  // namespace

VOBENCH_FILTER_PLUGIN(MotionBlur)
