// resolution_scale — a lower-resolution sensor: colour by area averaging, depth by nearest neighbour
// (averaging depth across an edge would invent surfaces), and the camera scaled with them (pixel
// centres kept: c' = (c + 0.5) s - 0.5).
#include "filter_pixels.hpp"

#include <algorithm>
#include <vector>

namespace {

class ResolutionScale : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {"resolution_scale",
                "1.0.0",
                "Scales the frames down (colour by area, depth by nearest neighbour) and the camera with them.",
                "MIT",
                "",
                {{"scale", VOBENCH_PARAM_DOUBLE, "0.5", 0.05, 1, "", "output size over input size (1: unchanged)"}}};
    }
    void start(const vobench_camera& camera, const vobench::sdk::Params& p, uint64_t) override {
        scale_ = p.get_double("scale");
        in_ = camera;
        out_ = camera;
        out_.width = std::max(1, static_cast<int>(std::lround(camera.width * scale_)));
        out_.height = std::max(1, static_cast<int>(std::lround(camera.height * scale_)));
        sx_ = static_cast<double>(out_.width) / camera.width;
        sy_ = static_cast<double>(out_.height) / camera.height;
        out_.fx = camera.fx * sx_;
        out_.fy = camera.fy * sy_;
        out_.cx = (camera.cx + 0.5) * sx_ - 0.5;
        out_.cy = (camera.cy + 0.5) * sy_ - 0.5;
    }
    vobench_camera output_camera(const vobench_camera&) const override { return out_; }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (out_.width == in_.width && out_.height == in_.height) return &in;
        buffer_.copy_from(in);  // packed rows of the input
        const vobench_image& ci = buffer_.color_image();
        const vobench_image& di = buffer_.depth_image();
        const int ch = ci.format == VOBENCH_PIXEL_GRAY8 ? 1 : 3, dbytes = di.format == VOBENCH_PIXEL_DEPTH_U16 ? 2 : 4;
        const int W = out_.width, H = out_.height;
        color_.assign(static_cast<std::size_t>(W) * H * ch, 0);
        depth_.assign(static_cast<std::size_t>(W) * H * dbytes, 0);
        for (int y = 0; y < H; ++y) {
            const int y0 = static_cast<int>(y / sy_), y1 = std::max(y0 + 1, std::min(ci.height, static_cast<int>((y + 1) / sy_)));
            for (int x = 0; x < W; ++x) {
                const int x0 = static_cast<int>(x / sx_), x1 = std::max(x0 + 1, std::min(ci.width, static_cast<int>((x + 1) / sx_)));
                for (int k = 0; k < ch; ++k) {
                    int sum = 0, n = 0;
                    for (int yy = y0; yy < y1; ++yy)
                        for (int xx = x0; xx < x1; ++xx, ++n)
                            sum += buffer_.color()[(static_cast<std::size_t>(yy) * ci.width + xx) * ch + k];
                    color_[(static_cast<std::size_t>(y) * W + x) * ch + k] = static_cast<uint8_t>((sum + n / 2) / std::max(1, n));
                }
                const int ny = std::min(di.height - 1, static_cast<int>((y + 0.5) / sy_)),
                          nx = std::min(di.width - 1, static_cast<int>((x + 0.5) / sx_));
                std::copy_n(buffer_.depth() + (static_cast<std::size_t>(ny) * di.width + nx) * dbytes, dbytes,
                            depth_.data() + (static_cast<std::size_t>(y) * W + x) * dbytes);
            }
        }
        color_image_ = ci;
        color_image_.width = W;
        color_image_.height = H;
        color_image_.stride_bytes = W * ch;
        color_image_.data = color_.data();
        depth_image_ = di;
        depth_image_.width = W;
        depth_image_.height = H;
        depth_image_.stride_bytes = W * dbytes;
        depth_image_.data = depth_.data();
        frame_ = in;
        frame_.color = &color_image_;
        frame_.depth = &depth_image_;
        return &frame_;
    }

private:
    double scale_ = 1, sx_ = 1, sy_ = 1;
    vobench_camera in_{}, out_{};
    vobench::sdk::FrameBuffer buffer_;
    std::vector<uint8_t> color_, depth_;
    vobench_image color_image_{}, depth_image_{};
    vobench_frame frame_{};
};

}  // namespace

VOBENCH_FILTER_PLUGIN(ResolutionScale)
