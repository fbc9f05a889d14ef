// depth_noise — adds Gaussian depth noise growing with the square of the range, σ(z) = k z² (the
// structured-light model of Khoshelham & Elberink 2012, k ≈ 1.425e-3 m⁻¹ for Kinect v1), re-quantised
// to the frame's depth unit.
#include "filter_pixels.hpp"

namespace {

class DepthNoise : public vobench::sdk::Filter {
public:
    static vobench::sdk::PluginInfo info() {
        return {"depth_noise",
                "1.0.0",
                "Gaussian depth noise sigma = k z^2 (Khoshelham & Elberink 2012), re-quantised to the depth unit.",
                "MIT",
                "",
                {{"k", VOBENCH_PARAM_DOUBLE, "0.001425", 0, 1, "", "sigma per squared metre of range, 1/m (Kinect v1: 1.425e-3)"}}};
    }
    void start(const vobench_camera&, const vobench::sdk::Params& p, uint64_t seed) override {
        k_ = p.get_double("k");
        seed_ = seed;
    }
    const vobench_frame* apply(const vobench_frame& in) override {
        if (k_ <= 0) return &in;
        buffer_.copy_from(in);
        const vobench_frame& f = buffer_.frame();
        uint8_t* depth = buffer_.depth();
        auto rng = vobench::filters::frame_rng(seed_, f.index);
        std::normal_distribution<double> unit(0.0, 1.0);
        for (std::size_t i = 0; i < vobench::filters::pixels(f); ++i) {
            const double z = vobench::filters::depth_m(f, depth, i);
            const double n = unit(rng);  // drawn for every pixel: the noise of a pixel does not depend on others' holes
            if (z > 0) vobench::filters::set_depth_m(f, depth, i, std::max(1e-3, z + k_ * z * z * n));
        }
        return &buffer_.frame();
    }

private:
    double k_ = 0;
    uint64_t seed_ = 0;
    vobench::sdk::FrameBuffer buffer_;
};

}  // namespace

VOBENCH_FILTER_PLUGIN(DepthNoise)
