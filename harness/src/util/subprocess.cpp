#include "util/subprocess.hpp"

#include <boost/dll/runtime_symbol_info.hpp>

#include <fcntl.h>
#include <sched.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace vobench {
namespace fs = std::filesystem;

std::string signal_name(int signal) {
    const char* abbrev = sigabbrev_np(signal);
    return abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(signal);
}

std::string ChildResult::describe() const {
    if (cancelled) return "cancelled (killed)";
    if (signal_blame != 0) return "sent " + signal_name(signal_blame) + " to the harness (killed)";
    if (log_exceeded)
        return "wrote more than the log limit of " + std::to_string(max_log_bytes >> 20) + " MB to stdout/stderr" +
               (exited ? "" : " (killed)");
    if (timed_out) return "timed out after " + std::to_string(timeout_s) + " s (killed)";
    if (memory_exceeded) return "exceeded the memory limit of " + std::to_string(memory_mb) + " MB (killed)";
    if (exited) return "exited with code " + std::to_string(exit_code);
    return "killed by signal " + std::to_string(signal) + " (" + signal_name(signal) + ")";
}

namespace {

// The contained children now running, for blame_signal_sender(): lock-free, so a signal handler
// can read it.
struct Slot {
    std::atomic<pid_t> leader{0};
    std::atomic<int> blame{0};
};
constexpr std::size_t kSlots = 1024;
Slot g_slots[kSlots];

Slot* take_slot(pid_t pid) {
    for (Slot& s : g_slots) {
        pid_t free = 0;
        if (s.leader.compare_exchange_strong(free, pid)) {
            s.blame = 0;
            return &s;
        }
    }
    return nullptr;  // more than kSlots cells at once: containment still works, only blame does not
}

}  // namespace

bool blame_signal_sender(int signal, int sender) noexcept {
    if (sender <= 0) return false;
    // getsid and getpgid are plain system calls; the sender is usually still alive while its kill()
    // is delivered.
    const pid_t sid = ::getsid(sender), pgid = ::getpgid(sender);
    for (Slot& s : g_slots) {
        const pid_t leader = s.leader.load();
        if (leader > 0 && (sender == leader || sid == leader || pgid == leader)) {
            s.blame = signal;
            return true;
        }
    }
    return false;
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

struct ProcEntry {
    pid_t pid = 0, ppid = 0, pgrp = 0, session = 0;
    char state = '?';
};

// /proc/<pid>/stat: the fields after the command name, which may itself hold spaces and ')'.
bool read_proc_stat(pid_t pid, ProcEntry& e) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(in, line)) return false;
    const auto close = line.rfind(')');
    if (close == std::string::npos) return false;
    std::istringstream rest(line.substr(close + 1));
    e.pid = pid;
    return static_cast<bool>(rest >> e.state >> e.ppid >> e.pgrp >> e.session);
}

bool has_tag(pid_t pid, const std::string& tag) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/environ", std::ios::binary);
    for (std::string var; std::getline(in, var, '\0');)
        if (var == tag) return true;
    return false;
}

// Every process that belongs to the contained child `leader` (not the leader itself): in its session
// or process group, or an orphan re-parented to this process that carries its tag.
std::vector<ProcEntry> group_members(pid_t leader, const std::string& tag) {
    std::vector<ProcEntry> out;
    const pid_t self = ::getpid();
    std::error_code ec;
    for (fs::directory_iterator it("/proc", ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.empty() || !std::isdigit(static_cast<unsigned char>(name[0]))) continue;
        ProcEntry e;
        if (!read_proc_stat(static_cast<pid_t>(std::stol(name)), e) || e.pid == leader) continue;
        if (e.session == leader || e.pgrp == leader || (e.ppid == self && has_tag(e.pid, tag))) out.push_back(e);
    }
    return out;
}

// Kills every member, reaps those that are ours, until none is left (or 3 s passed). Returns how many
// were still running (not zombies) at the first look.
std::size_t kill_members(pid_t leader, const std::string& tag) {
    std::size_t running = 0;
    const pid_t self = ::getpid();
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    for (bool first = true; std::chrono::steady_clock::now() < until; first = false) {
        const std::vector<ProcEntry> members = group_members(leader, tag);
        if (members.empty()) break;
        for (const ProcEntry& m : members) {
            if (first && m.state != 'Z') ++running;
            ::kill(m.pid, SIGKILL);
            if (m.ppid == self) ::waitpid(m.pid, nullptr, WNOHANG);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return running;
}

uint64_t group_resident_kb(pid_t leader, const std::vector<ProcEntry>& members) {
    uint64_t kb = resident_kb(leader);
    for (const ProcEntry& m : members) kb += resident_kb(m.pid);
    return kb;
}

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

    // A contained child carries a tag that only it and its descendants have, so that an orphan
    // that left its session is still known as the cell's.
    static std::atomic<uint64_t> serial{0};
    const std::string tag = "VOBENCH_CELL_TAG=" + std::to_string(::getpid()) + "." + std::to_string(serial++);
    std::vector<std::string> env_storage;
    for (char** e = environ; *e; ++e)
        if (std::strncmp(*e, "VOBENCH_CELL_TAG=", 17) != 0 && std::strncmp(*e, "VOBENCH_CELL_CPU=", 17) != 0) env_storage.emplace_back(*e);
    if (limits.contain) env_storage.push_back(tag);
    if (limits.cpu >= 0) env_storage.push_back("VOBENCH_CELL_CPU=" + std::to_string(limits.cpu));
    std::vector<char*> envp;
    for (std::string& e : env_storage) envp.push_back(e.data());
    envp.push_back(nullptr);
    if (limits.contain) ::prctl(PR_SET_CHILD_SUBREAPER, 1);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    const std::string log = limits.log.empty() ? "/dev/null" : limits.log.string();
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    // Its own session (contained) or process group, so that the terminal's SIGINT does not reach it
    // (see ChildLimits::cancel) and the whole group can be killed at once.
    if (limits.contain) {
        posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSID);
    } else {
        posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
        posix_spawnattr_setpgroup(&attributes, 0);
    }
    pid_t pid = 0;
    const auto start = std::chrono::steady_clock::now();
    const int rc = search ? posix_spawnp(&pid, exe.c_str(), &actions, &attributes, argv.data(), envp.data())
                          : posix_spawn(&pid, exe.c_str(), &actions, &attributes, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (rc != 0) throw std::runtime_error("cannot start " + exe + ": " + std::strerror(rc));
    Slot* slot = limits.contain ? take_slot(pid) : nullptr;

    ChildResult result;
    result.timeout_s = limits.timeout_s;
    result.memory_mb = limits.memory_mb;
    result.max_log_bytes = limits.max_log_bytes;
    const auto deadline = start + std::chrono::seconds(limits.timeout_s);
    int status = 0;
    std::vector<ProcEntry> members;
    for (unsigned tick = 0;; ++tick) {
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid) break;
        if (done < 0 && errno != EINTR) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
        result.peak_rss_kb = std::max(result.peak_rss_kb, peak_resident_kb(std::to_string(pid)));
        // Every 100 ms: the group's members (their memory counts), and the log's size.
        const bool slow_tick = tick % 20 == 0;
        if (limits.contain && slow_tick) members = group_members(pid, tag);
        uint64_t resident = limits.contain ? group_resident_kb(pid, members) : resident_kb(pid);
        if (limits.contain) result.peak_rss_kb = std::max(result.peak_rss_kb, resident);
        if (limits.cancel && limits.cancel->load()) {
            result.cancelled = true;
        } else if (slot && slot->blame.load() != 0) {
            result.signal_blame = slot->blame.load();
        } else if (std::chrono::steady_clock::now() >= deadline) {
            result.timed_out = true;
        } else if (limits.memory_mb > 0 && resident > limits.memory_mb * 1024) {
            result.memory_exceeded = true;
        } else if (slow_tick && limits.max_log_bytes > 0 && !limits.log.empty()) {
            std::error_code ec;
            result.log_exceeded = fs::file_size(limits.log, ec) > limits.max_log_bytes && !ec;
        }
        if (result.timed_out || result.memory_exceeded || result.cancelled || result.signal_blame || result.log_exceeded) {
            ::kill(-pid, SIGKILL);  // the whole process group (the child leads one either way)
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    decode_status(status, result);
    // A burst between two checks: the limit holds at the end too.
    if (!result.log_exceeded && limits.max_log_bytes > 0 && !limits.log.empty()) {
        std::error_code ec;
        result.log_exceeded = fs::file_size(limits.log, ec) > limits.max_log_bytes && !ec;
    }
    if (limits.contain) {
        const bool killed_by_us =
            result.timed_out || result.memory_exceeded || result.cancelled || result.signal_blame || result.log_exceeded;
        // Counted before anything is killed (a killed leftover is a zombie by the time it is looked at),
        // then every member killed and reaped: kill_members does both, in that order.
        const std::size_t running = kill_members(pid, tag);
        if (!killed_by_us) result.left_behind = running;
        if (slot) slot->leader = 0;
    }
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

fs::path self_executable() {
    // $VOBENCH_EXECUTABLE: a program that embeds the harness (the test binary) names the CLI to run.
    const char* self = std::getenv("VOBENCH_EXECUTABLE");
    return self && *self ? fs::path(self) : fs::path(boost::dll::program_location().string());
}

fs::path worker_executable() {
    const char* worker = std::getenv("VOBENCH_WORKER");
    return worker && *worker ? fs::path(worker) : self_executable().parent_path() / "vobench-worker";
}

ChildResult run_self_limited(const std::vector<std::string>& args, const ChildLimits& limits) {
    std::vector<std::string> argv{self_executable().string()};
    argv.insert(argv.end(), args.begin(), args.end());
    return spawn_limited(argv, limits, false);
}

ChildResult run_worker_limited(const std::vector<std::string>& args, const ChildLimits& limits) {
    std::vector<std::string> argv{worker_executable().string()};
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
    limits.contain = true;
    limits.log = temporary_log();
    ChildResult result = run_self_limited(args, limits);
    take_output(result, limits.log);
    return result;
}

std::vector<int> allowed_cpus() {
    std::vector<int> cpus;
    cpu_set_t set;
    CPU_ZERO(&set);
    if (::sched_getaffinity(0, sizeof(set), &set) == 0)
        for (int c = 0; c < CPU_SETSIZE; ++c)
            if (CPU_ISSET(c, &set)) cpus.push_back(c);
    return cpus;
}

int pin_to_cell_cpu() {
    const char* env = std::getenv("VOBENCH_CELL_CPU");
    if (env == nullptr || *env == '\0') return -1;
    char* end = nullptr;
    const long cpu = std::strtol(env, &end, 10);
    if (*end != '\0' || cpu < 0 || cpu >= CPU_SETSIZE) return -1;
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<int>(cpu), &set);
    return ::sched_setaffinity(0, sizeof(set), &set) == 0 ? static_cast<int>(cpu) : -1;
}

}  // namespace vobench
