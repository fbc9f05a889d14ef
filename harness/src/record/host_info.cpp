#include "record/host_info.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <sys/utsname.h>
#include <unistd.h>
#include <chrono>
#include <fstream>
#include <thread>

#ifndef VOBENCH_VERSION
#define VOBENCH_VERSION "unknown"
#endif

namespace vobench {

std::string vobench_version() { return VOBENCH_VERSION; }

std::string utc_now_iso() {
    const auto now = std::chrono::system_clock::now();
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
    return fmt::format("{:%Y-%m-%dT%H:%M:%S}.{:03d}Z", fmt::gmtime(std::chrono::system_clock::to_time_t(now)), ms);
}

nlohmann::json host_info() {
    std::string cpu = "unknown";
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    uint64_t memory_kb = 0;
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        if (key == "MemTotal:") {
            meminfo >> memory_kb;
            break;
        }
        meminfo.ignore(1 << 10, '\n');
    }
    utsname u{};
    ::uname(&u);
    char host[256] = {0};
    ::gethostname(host, sizeof(host) - 1);
    const std::string version = VOBENCH_VERSION;
    const auto plus = version.find('+');
    return {{"cpu", cpu},
            {"cores", std::thread::hardware_concurrency()},
            {"memory_mb", memory_kb / 1024},
            {"os", fmt::format("{} {} {}", u.sysname, u.release, u.machine)},
            {"hostname", host},
            {"compiler", fmt::format("{} {}", __GNUC__ >= 1 ? "gcc-compatible" : "unknown", __VERSION__)},
            {"vobench_version", version},
            {"git_revision", plus == std::string::npos ? "unknown" : version.substr(plus + 1)}};
}

}  // namespace vobench
