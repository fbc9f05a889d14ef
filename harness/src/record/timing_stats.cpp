#include "record/timing_stats.hpp"

#include "metrics/statistics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <string>
#include <thread>

namespace vobench {
namespace {

std::string first_line(const char* file) {
    std::ifstream in(file);
    std::string line;
    return std::getline(in, line) ? line : "";
}

// "model name" and "cpu MHz" of the first CPU in /proc/cpuinfo.
std::pair<std::string, double> cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    std::string model = "unknown";
    double mhz = 0;
    for (std::string line; std::getline(in, line);) {
        const auto colon = line.find(':');
        if (colon == std::string::npos || colon + 2 > line.size()) continue;
        if (line.rfind("model name", 0) == 0 && model == "unknown") model = line.substr(colon + 2);
        if (line.rfind("cpu MHz", 0) == 0 && mhz == 0) {
            try {
                mhz = std::stod(line.substr(colon + 2));
            } catch (const std::exception&) {}
        }
    }
    return {model, mhz};
}

nlohmann::json stats_of(std::vector<double> v) {
    if (v.empty()) return {{"mean", 0.0}, {"p95", 0.0}, {"max", 0.0}};
    const metrics::ErrorStats s = metrics::compute_stats(v);
    return {{"mean", s.mean}, {"p95", metrics::percentile_nearest_rank(v, 0.95)}, {"max", s.max}};
}

}  // namespace

nlohmann::json timing_statistics(const std::vector<FrameRecord>& frames, const TimingSpec& timing) {
    std::vector<double> ms, cpu_ms;
    std::size_t processed = 0, dropped = 0;
    std::vector<std::string> order;
    std::map<std::string, double> stage_ns;
    for (const FrameRecord& f : frames) {
        if (f.dropped) {
            ++dropped;
            continue;
        }
        if (processed++ < timing.warmup_frames) continue;  // first-call costs: recorded as excluded, not timed
        ms.push_back(static_cast<double>(f.process_ns) * 1e-6);
        if (f.cpu_ns >= 0) cpu_ms.push_back(static_cast<double>(f.cpu_ns) * 1e-6);
        for (const auto& [name, ns] : f.stages) {
            if (!stage_ns.count(name)) order.push_back(name);
            stage_ns[name] += static_cast<double>(ns);
        }
    }
    const double n = static_cast<double>(std::max<std::size_t>(1, ms.size()));
    nlohmann::json stages = nlohmann::json::array();
    for (const std::string& s : order) stages.push_back({{"stage", s}, {"mean_ms", stage_ns[s] * 1e-6 / n}});
    const metrics::ErrorStats stats = ms.empty() ? metrics::ErrorStats{} : metrics::compute_stats(ms);  // numpy semantics
    double cpu_total = 0, wall_total = 0;
    for (double v : cpu_ms) cpu_total += v;
    if (cpu_ms.size() == ms.size())
        for (double v : ms) wall_total += v;
    nlohmann::json j{{"frames_timed", ms.size()},
                     {"mean_ms", stats.mean},
                     {"median_ms", stats.median},
                     {"p95_ms", ms.empty() ? 0.0 : metrics::percentile_nearest_rank(ms, 0.95)},
                     {"max_ms", stats.max},
                     {"fps", stats.mean > 0 ? 1000.0 / stats.mean : 0.0},
                     {"processed_frames", processed},
                     {"dropped_frames", dropped},
                     {"stages", stages}};
    if (!cpu_ms.empty()) {
        j["cpu_ms"] = cpu_total / static_cast<double>(cpu_ms.size());
        if (wall_total > 0) j["cpu_per_wall"] = cpu_total / wall_total;
    }
    // Real time: the plugin starts on a frame when it arrives (it was free), so arrival to pose is the call.
    if (timing.mode == "realtime") j["latency_ms"] = stats_of(ms);
    return j;
}

nlohmann::json timing_protocol(const TimingSpec& timing, int threads_allowed, const nlohmann::json& affinity, int pinned_core) {
    const auto [model, mhz] = cpu_model();
    const std::string governor = first_line("/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor");
    nlohmann::json j{{"mode", timing.mode},
                     {"warmup_frames", timing.warmup_frames},
                     {"timed", "the plugin's process() call only: steady clock, ns; reading and decoding frames is outside the window"},
                     {"cpu_time", "CLOCK_PROCESS_CPUTIME_ID during the call, less the frame-reading thread's"},
                     {"threads_allowed", threads_allowed},
                     {"cpu_model", model},
                     {"cpu_mhz", mhz},
                     {"governor", governor.empty() ? "not exposed by this machine" : governor},
                     {"cores_online", std::thread::hardware_concurrency()},
                     {"pinned_core", pinned_core},
                     {"affinity", affinity.is_array() ? affinity : nlohmann::json::array()}};
    if (timing.mode == "realtime") {
        j["speed"] = timing.speed;
        j["realtime"] =
            "frame i arrives at (stamp_i - stamp_0) / speed on a clock advanced by the measured process() times; a frame arriving "
            "while the plugin is busy is dropped (not given to it, no pose)";
    }
    return j;
}

}  // namespace vobench
