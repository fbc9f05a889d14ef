// time_offset — pairs each colour image with the depth image of `frames` frames earlier (colour and
// depth out of step, as unsynchronised sensors are), its depth_timestamp with it. The first frames, which
// have no older depth, keep their own.
#include "filter_pixels.hpp"

#include <deque>
#include <vector>

namespace {

class TimeOffset : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {
            "time_offset", "1.0.0", "Pairs each colour image with the depth image of N frames earlier (colour-depth time offset).",
            "MIT",         "",      {{"frames", VOBENCH_PARAM_INT, "1", 0, 100, "", "how many frames older the depth is (0: unchanged)"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& p, uint64_t) override {
        frames_ = static_cast<std::size_t>(p.get_int("frames"));
    }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (frames_ == 0) return &in;
        // Keep this frame's depth for later frames.
        vobench::sdk::FrameBuffer copy;
        copy.copy_from(in);
        history_.push_back({std::vector<uint8_t>(copy.depth(), copy.depth() + copy.depth_image().stride_bytes * copy.depth_image().height),
                            copy.depth_image(), in.depth_timestamp});
        if (history_.size() > frames_ + 1) history_.pop_front();
        if (history_.size() <= frames_) return &in;  // no depth that old yet
        Old& old = history_.front();
        buffer_.copy_from(in);
        out_depth_ = old.bytes;
        depth_ = old.image;
        depth_.data = out_depth_.data();
        buffer_.frame().depth = &depth_;
        buffer_.frame().depth_timestamp = old.stamp;
        return &buffer_.frame();
    }

private:
    struct Old {
        std::vector<uint8_t> bytes;
        vobench_image image;
        double stamp;
    };
    std::size_t frames_ = 0;
    std::deque<Old> history_;
    std::vector<uint8_t> out_depth_;
    vobench_image depth_{};
    vobench::sdk::FrameBuffer buffer_;
};

}  // namespace

VOBENCH_FILTER_PLUGIN(TimeOffset)
