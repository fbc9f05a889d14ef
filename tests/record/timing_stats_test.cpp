// Timing statistics: over the frames given to the plugin, after the warm-up; dropped frames counted,
// not timed; CPU over wall only where every timed frame has a CPU time; latency in real-time mode.
#include "record/timing_stats.hpp"

#include <catch2/catch.hpp>

using namespace vobench;

namespace {
FrameRecord frame(uint64_t i, double ms, double cpu_ms = -1, bool dropped = false) {
    FrameRecord f;
    f.index = i;
    f.process_ns = static_cast<int64_t>(ms * 1e6);
    f.cpu_ns = cpu_ms < 0 ? -1 : static_cast<int64_t>(cpu_ms * 1e6);
    f.dropped = dropped;
    return f;
}
}  // namespace

TEST_CASE("timing statistics leave out the warm-up and the dropped frames", "[record][timing]") {
    const std::vector<FrameRecord> frames = {frame(0, 100, 100), frame(1, 2, 4), frame(2, 0, -1, true), frame(3, 4, 8), frame(4, 6, 12)};
    TimingSpec spec;
    spec.warmup_frames = 1;
    const nlohmann::json j = timing_statistics(frames, spec);
    CHECK(j["processed_frames"] == 4);
    CHECK(j["dropped_frames"] == 1);
    CHECK(j["frames_timed"] == 3);
    CHECK(j["mean_ms"].get<double>() == Approx(4.0));
    CHECK(j["median_ms"].get<double>() == Approx(4.0));
    CHECK(j["max_ms"].get<double>() == Approx(6.0));
    CHECK(j["cpu_per_wall"].get<double>() == Approx(2.0));  // a plugin on two threads
    CHECK_FALSE(j.contains("latency_ms"));
    spec.mode = "realtime";
    const nlohmann::json rt = timing_statistics(frames, spec);
    CHECK(rt["latency_ms"]["mean"].get<double>() == Approx(4.0));
    CHECK(rt["latency_ms"]["max"].get<double>() == Approx(6.0));
}

TEST_CASE("the timing protocol names what was timed and how", "[record][timing]") {
    TimingSpec spec;
    spec.mode = "realtime";
    spec.speed = 2;
    const nlohmann::json p = timing_protocol(spec, 1, nlohmann::json::array({0, 1}), 1);
    CHECK(p["mode"] == "realtime");
    CHECK(p["speed"] == 2.0);
    CHECK(p["threads_allowed"] == 1);
    CHECK(p["pinned_core"] == 1);
    CHECK(p["affinity"] == nlohmann::json::array({0, 1}));
    CHECK(p["cpu_model"].is_string());
    CHECK(p["governor"].is_string());
    CHECK(p["timed"].get<std::string>().find("process()") != std::string::npos);
}
