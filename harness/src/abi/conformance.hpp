// conformance.hpp — `vobench plugins check`: exercises any plugin library against the ABI rules
// (DESIGN.md rule 12): entry and versions, struct sizes, the parameter table, create/destroy twice,
// error paths, and (for odometry) a few synthetic frames; for datasets, a real sequence when given.
//
// run_conformance() runs in-process and prints one line per step, flushed, so that a parent process
// that sees the plugin crash knows the last step reached (check_in_child()).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>

namespace vobench {

struct ConformanceOptions {
    std::filesystem::path library;
    std::optional<std::string> dataset_path;    // a sequence to open and read (dataset plugins)
    int timeout_s = 120;                        // child process only
    std::filesystem::path verdict_file;         // in-process: "0" or "1" written here after the last step
    std::map<std::string, std::string> params;  // for the instances that start or open (e.g. python module=FILE)
};

// In this process. Returns 0 when every step passes, 1 otherwise.
int run_conformance(const ConformanceOptions& options, std::ostream& out);

// In a child process (`vobench plugins check --in-process ...`): a crash, an abort, a hang, or an
// exit() of any code inside a plugin call becomes a failed report (the child's verdict file, written
// after the last step, is what says the check ran to its end). Ends with one line "PASS …" or
// "FAIL …". Returns the exit status for the CLI: 0 pass, 1 fail.
int check_in_child(const ConformanceOptions& options, std::ostream& out);

}  // namespace vobench
