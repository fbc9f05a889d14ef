// app_setup.hpp — what the two programs (vobench, vobench-worker) share around their commands: logs to
// stderr (so --json output on stdout stays machine-readable) with -v/-q, and one way of parsing and
// turning an exception into a message and exit status 1.
#pragma once

#include <CLI/CLI.hpp>

namespace vobench::cli {

// The stderr logger and the -v/--verbose, -q/--quiet flags on `app`.
void setup_logging(CLI::App& app);

// Parses argv, which runs the chosen command; returns its exit status, CLI11's for a usage error, or 1
// (with the message logged) when the command throws.
int parse_and_run(CLI::App& app, int argc, char** argv, const int& exit_code);

}  // namespace vobench::cli
