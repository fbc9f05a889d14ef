// frame_drops — drops frames, singly or in bursts (a USB hiccup, a busy driver), at a long-run rate.
// Frame 0 is never dropped: it defines the world frame.
#include "filter_pixels.hpp"

namespace {

class FrameDrops : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {"frame_drops",
                "1.0.0",
                "Drops frames at a long-run rate, in bursts of a given mean length; never frame 0.",
                "MIT",
                "",
                {{"rate", VOBENCH_PARAM_DOUBLE, "0.1", 0, 0.95, "", "share of frames dropped in the long run"},
                 {"burst", VOBENCH_PARAM_INT, "1", 1, 1000, "", "mean number of frames in a burst of drops (geometric)"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& p, uint64_t seed) override {
        rate_ = p.get_double("rate");
        burst_ = static_cast<double>(p.get_int("burst"));
        seed_ = seed;
    }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (in.index == 0 || rate_ <= 0) return &in;
        auto rng = vobench::filters::frame_rng(seed_, in.index);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        // Two states: a burst ends with probability 1/burst; one starts with the probability that
        // makes the stationary share of dropped frames `rate`.
        const double end = 1.0 / burst_, begin = rate_ * end / (1.0 - rate_);
        dropping_ = dropping_ ? u(rng) >= end : u(rng) < begin;
        return dropping_ ? nullptr : &in;
    }

private:
    double rate_ = 0, burst_ = 1;
    uint64_t seed_ = 0;
    bool dropping_ = false;
};

}  // namespace

VOBENCH_FILTER_PLUGIN(FrameDrops)
