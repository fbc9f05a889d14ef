// libFuzzer target: the trajectory parsers (TUM, KITTI, EuRoC, PUTK² raw, in both reader modes) must
// either parse or throw TrajectoryError — never crash, hang or read out of bounds.
#include "metrics/trajectory_io.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    using namespace vobench::metrics;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    ReadOptions o;
    o.format = static_cast<TrajectoryFormat>(data[0] % 4);
    o.tum_scripts = (data[0] & 0x10) != 0;
    try {
        parse_trajectory(text, "fuzz", o);
    } catch (const TrajectoryError&) {}
    return 0;
}
