// host_info.hpp — what a result was measured on: CPU, memory, OS, compiler, vobench build.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace vobench {

// {"cpu": "...", "cores": 2, "memory_mb": ..., "os": "Linux 6.1 x86_64", "hostname": ..., "compiler": ...,
//  "vobench_version": ..., "git_revision": ...}
nlohmann::json host_info();

std::string vobench_version();  // "0.1.0+abc1234"
std::string utc_now_iso();      // "2026-11-22T03:04:05.123Z"

}  // namespace vobench
