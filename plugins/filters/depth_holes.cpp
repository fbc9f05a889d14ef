// depth_holes — removes a fraction of the valid depth readings, in discs of a given radius (clustered,
// as real holes are: dark, shiny or glancing surfaces) or pixel by pixel (radius 0).
#include "filter_pixels.hpp"

#include <algorithm>

namespace {

class DepthHoles : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {"depth_holes",
                "1.0.0",
                "Removes a fraction of the valid depth readings, in discs (clustered) or single pixels.",
                "MIT",
                "",
                {{"fraction", VOBENCH_PARAM_DOUBLE, "0.1", 0, 1, "", "share of the valid depth pixels removed"},
                 {"radius", VOBENCH_PARAM_INT, "6", 0, 200, "", "radius of a hole in pixels (0: independent pixels)"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& p, uint64_t seed) override {
        fraction_ = p.get_double("fraction");
        radius_ = static_cast<int>(p.get_int("radius"));
        seed_ = seed;
    }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (fraction_ <= 0) return &in;
        buffer_.copy_from(in);
        const vobench_frame& f = buffer_.frame();
        uint8_t* depth = buffer_.depth();
        const int w = f.depth->width, h = f.depth->height;
        std::size_t valid = 0;
        for (std::size_t i = 0; i < vobench::filters::pixels(f); ++i) valid += vobench::filters::depth_m(f, depth, i) > 0;
        const auto target = static_cast<std::size_t>(fraction_ * static_cast<double>(valid) + 0.5);
        auto rng = vobench::filters::frame_rng(seed_, f.index);
        std::uniform_int_distribution<int> ux(0, w - 1), uy(0, h - 1);
        std::size_t removed = 0;
        // Holes until the share is reached (bounded: a fraction near 1 needs many overlapping discs).
        for (std::size_t attempt = 0; removed < target && attempt < 50 * (target + 1); ++attempt) {
            const int cx = ux(rng), cy = uy(rng);
            for (int y = std::max(0, cy - radius_); y <= std::min(h - 1, cy + radius_) && removed < target; ++y)
                for (int x = std::max(0, cx - radius_); x <= std::min(w - 1, cx + radius_) && removed < target; ++x) {
                    if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > radius_ * radius_) continue;
                    const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
                    if (vobench::filters::depth_m(f, depth, i) > 0) {
                        vobench::filters::set_depth_m(f, depth, i, 0);
                        ++removed;
                    }
                }
        }
        host().counter("depth_removed", static_cast<double>(removed));
        return &buffer_.frame();
    }

private:
    double fraction_ = 0;
    int radius_ = 0;
    uint64_t seed_ = 0;
    vobench::sdk::FrameBuffer buffer_;
};

}  // namespace

VOBENCH_FILTER_PLUGIN(DepthHoles)
