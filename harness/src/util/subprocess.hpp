// subprocess.hpp — running this same executable as an isolated child (Boost.Process), with a
// wall-clock timeout, so that a plugin that crashes, aborts, exits or hangs cannot take vobench down.
#pragma once

#include <string>
#include <vector>

namespace vobench {

struct ChildResult {
    bool exited = false;      // exited normally (exit_code valid)
    int exit_code = -1;
    int signal = 0;           // the signal that ended it, when it did not exit
    bool timed_out = false;   // killed by us after the timeout
    std::string output;       // stdout and stderr, interleaved
    // "exited with code 3", "killed by signal 11 (SIGSEGV)", "timed out after 120 s" ...
    std::string describe() const;
};

// Runs <this executable> args..., waiting at most timeout_s seconds (then SIGKILL).
ChildResult run_self(const std::vector<std::string>& args, int timeout_s);

}  // namespace vobench
