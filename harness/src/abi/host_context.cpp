#include "abi/host_context.hpp"

#include <spdlog/spdlog.h>

namespace vobench {

HostContext::HostContext(std::string plugin_name) : plugin_name_(std::move(plugin_name)) {
    services_.struct_size = sizeof(vobench_host_services);
    services_.context = this;
    services_.log = &HostContext::on_log;
    services_.stage_begin = &HostContext::on_stage_begin;
    services_.stage_end = &HostContext::on_stage_end;
    services_.counter = &HostContext::on_counter;
    services_.is_cancelled = &HostContext::on_is_cancelled;
}

void HostContext::begin_call() {
    open_.clear();
    stages_.clear();
    counters_.clear();
}

void HostContext::on_log(void* context, vobench_log_level level, const char* message) {
    auto* self = static_cast<HostContext*>(context);
    const char* text = message ? message : "";
    switch (level) {
        case VOBENCH_LOG_DEBUG: spdlog::debug("[{}] {}", self->plugin_name_, text); break;
        case VOBENCH_LOG_INFO: spdlog::info("[{}] {}", self->plugin_name_, text); break;
        case VOBENCH_LOG_WARNING: spdlog::warn("[{}] {}", self->plugin_name_, text); break;
        default: spdlog::error("[{}] {}", self->plugin_name_, text); break;
    }
}

void HostContext::on_stage_begin(void* context, const char* stage) {
    auto* self = static_cast<HostContext*>(context);
    if (self->open_.size() > kMaxTracked) return;  // a runaway plugin: the run fails on the count (run/track.cpp)
    self->open_.push_back({stage ? stage : "", std::chrono::steady_clock::now()});
}

void HostContext::on_stage_end(void* context, const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    auto* self = static_cast<HostContext*>(context);
    const std::string name = stage ? stage : "";
    // Close the innermost open stage of that name; an end without a begin is ignored.
    for (auto it = self->open_.rbegin(); it != self->open_.rend(); ++it) {
        if (it->name != name) continue;
        const int64_t ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now - it->start).count();
        self->open_.erase(std::next(it).base());
        for (auto& [n, total] : self->stages_)
            if (n == name) {
                total += ns;
                return;
            }
        if (self->stages_.size() <= kMaxTracked) self->stages_.emplace_back(name, ns);
        return;
    }
}

void HostContext::on_counter(void* context, const char* name, double value) {
    auto* self = static_cast<HostContext*>(context);
    const std::string key = name ? name : "";
    for (auto& [n, v] : self->counters_)
        if (n == key) {
            v = value;
            return;
        }
    // Past the limit one more name is kept, so that the host sees the limit crossed and fails the
    // run; the rest are dropped, so a call that emits 80,000 names costs no more than 257.
    if (self->counters_.size() <= kMaxTracked) self->counters_.emplace_back(key, value);
}

int32_t HostContext::on_is_cancelled(void* context) { return static_cast<HostContext*>(context)->cancelled_.load() ? 1 : 0; }

}  // namespace vobench
