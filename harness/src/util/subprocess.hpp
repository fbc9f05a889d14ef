// subprocess.hpp — running this same executable as an isolated child, with a wall-clock timeout and
// a resident-memory limit, so that a plugin that crashes, aborts, exits, hangs or eats memory cannot
// take vobench down.
//
// posix_spawn + waitpid rather than Boost.Process: one loop that reaps the child, enforces the timeout
// and the memory limit, and samples the child's own high-water mark (/proc/<pid>/status VmHWM). Not
// ru_maxrss: after a spawn, Linux carries the parent's peak into the child's ru_maxrss, so every child of
// a large vobench would report the parent's size.

#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

struct ChildLimits {
    int timeout_s = 600;        // wall clock; then SIGKILL
    uint64_t memory_mb = 0;     // resident set; 0: no limit. Checked every 5 ms; then SIGKILL
    std::filesystem::path log;  // stdout and stderr go here (a file, never a pipe that could fill)
    // When this becomes true the child is killed (SIGKILL) and the result says `cancelled`: how Ctrl-C
    // reaches cells, which run in their own process group so that the terminal's SIGINT does not.
    const std::atomic<bool>* cancel = nullptr;
    // Containment (a sweep's cells): the child starts its own session, carries a tag in its
    // environment, and everything it spawns belongs to it — the memory limit counts the whole group,
    // the timeout and the memory limit kill the whole group, and when the child ends every process
    // still in its session or group, or re-parented to this one with its tag, is killed and counted
    // (ChildResult::left_behind). This process becomes a child subreaper (PR_SET_CHILD_SUBREAPER) so
    // that orphans come back to it instead of to init.
    bool contain = false;
    uint64_t max_log_bytes = uint64_t{64} << 20;  // stdout + stderr; then SIGKILL (0: no limit)
    // >= 0: the child is told to run on this CPU only ($VOBENCH_CELL_CPU; a cell's child pins itself
    // before it starts a thread: pin_to_cell_cpu()).
    int cpu = -1;
};

// In a child started with ChildLimits::cpu: pins this process to that CPU (before any thread
// exists, so every thread inherits it). Returns the CPU, or -1 when none was asked or pinning failed.
int pin_to_cell_cpu();

// The CPUs this process may run on (sched_getaffinity).
std::vector<int> allowed_cpus();

struct ChildResult {
    bool exited = false;  // exited normally (exit_code valid)
    int exit_code = -1;
    int signal = 0;                // the signal that ended it, when it did not exit
    bool timed_out = false;        // killed by us after the timeout
    bool memory_exceeded = false;  // killed by us over the memory limit
    bool cancelled = false;        // killed by us because ChildLimits::cancel became true
    bool log_exceeded = false;     // killed by us: wrote more than max_log_bytes
    int signal_blame = 0;          // a process of the (contained) child sent this signal to us; killed
    std::size_t left_behind = 0;   // processes of the child still running when it ended (killed)
    uint64_t peak_rss_kb = 0;      // peak resident set (VmHWM of the child; with contain, of its whole group)
    double wall_s = 0;
    int timeout_s = 0;
    uint64_t memory_mb = 0;
    uint64_t max_log_bytes = 0;
    std::string output;  // run_self only: stdout and stderr, interleaved
    // "exited with code 3", "killed by signal 11 (SIGSEGV)", "timed out after 120 s",
    // "exceeded the memory limit of 512 MB" ...
    std::string describe() const;
};

// "SIGTERM", "SIGSEGV", … (or the number).
std::string signal_name(int signal);

// For a signal handler (async-signal-safe): when `sender` is a contained child that is running, or
// in its session or process group, marks that child to be killed with ChildResult::signal_blame =
// `signal` and returns true; otherwise returns false (the signal came from elsewhere: the user).
bool blame_signal_sender(int signal, int sender) noexcept;

// The high-water resident set of a live process (VmHWM, KiB); 0 if unreadable. Pass "self" for this one.
uint64_t peak_resident_kb(const std::string& pid);

// Runs <this executable> args... under `limits` ($VOBENCH_EXECUTABLE instead, when set: how a test
// binary that embeds the harness names the CLI). Throws std::runtime_error if it cannot start.
ChildResult run_self_limited(const std::vector<std::string>& args, const ChildLimits& limits);

// The vobench CLI this process counts as ($VOBENCH_EXECUTABLE, else this executable).
std::filesystem::path self_executable();
// vobench-worker, which runs the commands that need OpenCV and TBB (synth, cell-exec):
// $VOBENCH_WORKER, else beside self_executable().
std::filesystem::path worker_executable();
// As run_self_limited, for vobench-worker.
ChildResult run_worker_limited(const std::vector<std::string>& args, const ChildLimits& limits);

// Runs another program (looked up on PATH) with output captured into ChildResult::output.
// Throws std::runtime_error if it cannot start.
ChildResult run_program(const std::vector<std::string>& argv, int timeout_s);

// As above with the output captured into ChildResult::output (a temporary log file), contained
// (ChildLimits::contain): whatever the child leaves running when it ends is killed and counted in
// ChildResult::left_behind.
ChildResult run_self(const std::vector<std::string>& args, int timeout_s);

}  // namespace vobench
