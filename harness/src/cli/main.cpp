// vobench — the command-line host. See `vobench --help`.
#include "cli/app_setup.hpp"
#include "cli/commands.hpp"
#include "util/frame_memory.hpp"
#include "util/subprocess.hpp"

#include <vobench/vobench_plugin.h>

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ext/stdio_filebuf.h>

#include <iostream>

#ifndef VOBENCH_VERSION
#define VOBENCH_VERSION "unknown"
#endif

namespace vobench::cli {

std::map<std::string, std::string> parse_key_values(const std::vector<std::string>& items, const std::string& option) {
    std::map<std::string, std::string> out;
    for (const std::string& item : items) {
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0) throw CLI::ValidationError(option, "'" + item + "' is not of the form key=value");
        out[item.substr(0, eq)] = item.substr(eq + 1);
    }
    return out;
}

}  // namespace vobench::cli

namespace {

// The harness's own stdout, for std::cout only. File descriptor 1 itself is pointed at stderr, so
// that whatever plugin code prints (a library constructor, a reader's printf in `vobench track`)
// can never mix into --json output or a table. Close-on-exec: children never inherit it.
// The buffer lives until the process ends (std::cout is flushed after main returns).
void own_stdout() {
    const int fd = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3);
    if (fd < 0 || ::dup2(STDERR_FILENO, STDOUT_FILENO) < 0) return;
    std::cout.rdbuf(new __gnu_cxx::stdio_filebuf<char>(fd, std::ios::out));
}

// synth and cell-exec need OpenCV and TBB: they run in vobench-worker, so that no other command pays
// for loading them (vobench --version took 74 ms and 147 libraries with them linked in).
bool forwards_to_worker(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a.empty() || a[0] == '-') continue;
        return a == "synth" || a == "cell-exec";
    }
    return false;
}

}  // namespace

int main(int argc, char** argv) {
    if (forwards_to_worker(argc, argv)) {
        const std::string worker = vobench::worker_executable().string();
        argv[0] = const_cast<char*>(worker.c_str());
        ::execv(worker.c_str(), argv);
        std::fprintf(stderr, "vobench: cannot run %s: %s\n", worker.c_str(), std::strerror(errno));
        return 1;
    }
    vobench::keep_frame_buffers_allocated();  // `track` reads frame after frame in this process
    own_stdout();
    CLI::App app{"vobench — a benchmark harness for RGB-D visual odometry"};
    app.require_subcommand(0, 1);
    app.set_version_flag("--version", std::string("vobench ") + VOBENCH_VERSION + " (plugin ABI " + std::to_string(VOBENCH_ABI_VERSION) +
                                          ", API " + std::to_string(VOBENCH_API_VERSION) + ")");
    vobench::cli::setup_logging(app);

    int exit_code = 0;
    vobench::cli::add_plugins_commands(app, exit_code);
    vobench::cli::add_track_command(app, exit_code);
    vobench::cli::add_eval_command(app, exit_code);
    vobench::cli::add_traj_command(app, exit_code);
    vobench::cli::add_plot_command(app, exit_code);
    vobench::cli::add_data_command(app, exit_code);
    // Listed here for --help; forwarded to vobench-worker before parsing (forwards_to_worker).
    app.add_subcommand("synth", "Render a synthetic Kinect v1/v2 RGB-D sequence with ground truth (`vobench synth --help`)")
        ->allow_extras();
    vobench::cli::add_run_commands(app, exit_code);
    vobench::cli::add_gt_commands(app, exit_code);
    vobench::cli::add_new_plugin_command(app, exit_code);

    const int status = vobench::cli::parse_and_run(app, argc, argv, exit_code);
    if (argc == 1) std::cout << app.help();
    std::cout.flush();
    return status;
}
