#include "util/subprocess.hpp"

#include <boost/dll/runtime_symbol_info.hpp>

#include <chrono>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace vobench {
namespace fs = std::filesystem;

std::string ChildResult::describe() const {
    if (cancelled) return "cancelled (killed)";
    if (timed_out) return "timed out after " + std::to_string(timeout_s) + " s (killed)";
    if (memory_exceeded) return "exceeded the memory limit of " + std::to_string(memory_mb) + " MB (killed)";
    if (exited) return "exited with code " + std::to_string(exit_code);
    std::string name = sigabbrev_np(signal) ? std::string("SIG") + sigabbrev_np(signal) : "?";
    return "killed by signal " + std::to_string(signal) + " (" + name + ")";
}

namespace {

// Resident set of a live process in KiB, from /proc/<pid>/statm (pages); 0 if unreadable.
uint64_t resident_kb(pid_t pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/statm");
    uint64_t size = 0, resident = 0;
    if (!(in >> size >> resident)) return 0;
    return resident * static_cast<uint64_t>(::sysconf(_SC_PAGESIZE)) / 1024;
}

}  // namespace

uint64_t peak_resident_kb(const std::string& pid) {
    std::ifstream in("/proc/" + pid + "/status");
    for (std::string key; in >> key;) {
        if (key == "VmHWM:") {
            uint64_t kb = 0;
            in >> kb;
            return kb;
        }
        in.ignore(1 << 12, '\n');
    }
    return 0;
}

namespace {

void decode_status(int status, ChildResult& r) {
    if (WIFEXITED(status)) {
        r.exited = true;
        r.exit_code = WEXITSTATUS(status);
    } else if (WIFSIGNALED(status)) {
        r.signal = WTERMSIG(status);
    }
}

// posix_spawn(p) of argv_storage[0] with the limits; `search` looks the program up on PATH.
ChildResult spawn_limited(std::vector<std::string> argv_storage, const ChildLimits& limits, bool search) {
    const std::string exe = argv_storage.front();
    std::vector<char*> argv;
    for (std::string& a : argv_storage) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    const std::string log = limits.log.empty() ? "/dev/null" : limits.log.string();
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);  // its own process group (see ChildLimits::cancel)
    posix_spawnattr_setpgroup(&attributes, 0);
    pid_t pid = 0;
    const auto start = std::chrono::steady_clock::now();
    const int rc = search ? posix_spawnp(&pid, exe.c_str(), &actions, &attributes, argv.data(), environ)
                          : posix_spawn(&pid, exe.c_str(), &actions, &attributes, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (rc != 0) throw std::runtime_error("cannot start " + exe + ": " + std::strerror(rc));

    ChildResult result;
    result.timeout_s = limits.timeout_s;
    result.memory_mb = limits.memory_mb;
    const auto deadline = start + std::chrono::seconds(limits.timeout_s);
    int status = 0;
    for (;;) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        if (done < 0 && errno != EINTR) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
        result.peak_rss_kb = std::max(result.peak_rss_kb, peak_resident_kb(std::to_string(pid)));
        if (limits.cancel && limits.cancel->load()) {
            result.cancelled = true;
        } else if (std::chrono::steady_clock::now() >= deadline) {
            result.timed_out = true;
        } else if (limits.memory_mb > 0 && resident_kb(pid) > limits.memory_mb * 1024) {
            result.memory_exceeded = true;
        }
        if (result.timed_out || result.memory_exceeded || result.cancelled) {
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    decode_status(status, result);
    result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

fs::path temporary_log() {
    return fs::temp_directory_path() / ("vobench-child-" + std::to_string(::getpid()) + "-" +
                                        std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + ".log");
}

void take_output(ChildResult& result, const fs::path& log) {
    std::ifstream in(log);
    std::ostringstream ss;
    ss << in.rdbuf();
    result.output = ss.str();
    std::error_code ec;
    fs::remove(log, ec);
}

}  // namespace

ChildResult run_self_limited(const std::vector<std::string>& args, const ChildLimits& limits) {
    std::vector<std::string> argv{boost::dll::program_location().string()};
    argv.insert(argv.end(), args.begin(), args.end());
    return spawn_limited(argv, limits, false);
}

ChildResult run_program(const std::vector<std::string>& argv, int timeout_s) {
    ChildLimits limits;
    limits.timeout_s = timeout_s;
    limits.log = temporary_log();
    ChildResult result = spawn_limited(argv, limits, true);
    take_output(result, limits.log);
    return result;
}

ChildResult run_self(const std::vector<std::string>& args, int timeout_s) {
    ChildLimits limits;
    limits.timeout_s = timeout_s;
    limits.log = temporary_log();
    ChildResult result = run_self_limited(args, limits);
    take_output(result, limits.log);
    return result;
}

}  // namespace vobench
