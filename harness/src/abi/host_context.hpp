// host_context.hpp — the host services one plugin instance sees: logging (to spdlog, tagged with the
// plugin's name), per-call stage timing, per-call counters, and a cancel flag.
#pragma once

#include <vobench/vobench_plugin.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vobench {

class HostContext {
public:
    // Names kept per call (stages, counters, open stages); the 257th is kept so the limit shows.
    static constexpr std::size_t kMaxTracked = 256;

    explicit HostContext(std::string plugin_name);
    HostContext(const HostContext&) = delete;
    HostContext& operator=(const HostContext&) = delete;

    // The table handed to the plugin; valid as long as this object.
    const vobench_host_services* services() const { return &services_; }

    // Forget the stage times and counters of the previous call (the host calls this before each timed
    // call, outside the timed window).
    void begin_call();
    // Stage totals (ns) and counters of the last call, in first-seen order.
    const std::vector<std::pair<std::string, int64_t>>& stage_ns() const { return stages_; }
    const std::vector<std::pair<std::string, double>>& counters() const { return counters_; }
    // Stages begun but not ended by the plugin during the last call (a plugin bug, reported as a warning).
    std::size_t unbalanced_stages() const { return open_.size(); }

    void cancel() { cancelled_.store(true); }

private:
    static void on_log(void* context, vobench_log_level level, const char* message);
    static void on_stage_begin(void* context, const char* stage);
    static void on_stage_end(void* context, const char* stage);
    static void on_counter(void* context, const char* name, double value);
    static int32_t on_is_cancelled(void* context);

    struct OpenStage {
        std::string name;
        std::chrono::steady_clock::time_point start;
    };
    std::string plugin_name_;
    vobench_host_services services_{};
    std::vector<OpenStage> open_;
    std::vector<std::pair<std::string, int64_t>> stages_;
    std::vector<std::pair<std::string, double>> counters_;
    std::atomic<bool> cancelled_{false};
};

}  // namespace vobench
