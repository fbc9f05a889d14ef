// vobench-worker — the two commands that need OpenCV and TBB: rendering (`synth`) and a cell's child
// (`cell-exec`, which caps the threads OpenCV and TBB may use inside the cell). `vobench` forwards
// these commands here (execv), so that every other command — eval, traj, plugins, run, report —
// starts without loading OpenCV, GDAL and TBB. Not meant to be called by hand.
#include "cli/commands.hpp"
#include "sweep/cell_runner.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <iostream>

int main(int argc, char** argv) {
    spdlog::set_default_logger(spdlog::stderr_color_mt("vobench"));
    spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
    CLI::App app{"vobench-worker — vobench's rendering and cell processes (run through vobench)"};
    app.require_subcommand(1, 1);
    bool verbose = false, quiet = false;
    app.add_flag("-v,--verbose", verbose, "More log output");
    app.add_flag("-q,--quiet", quiet, "Only warnings and errors");
    app.parse_complete_callback([&] {
        spdlog::set_level(verbose ? spdlog::level::debug : quiet ? spdlog::level::warn : spdlog::level::info);
    });
    int exit_code = 0;
    vobench::cli::add_synth_command(app, exit_code);
    auto* exec = app.add_subcommand("cell-exec", "The child process of one cell (see sweep/cell_runner.hpp)");
    static std::string work_dir;
    exec->add_option("work_dir", work_dir)->required();
    exec->callback([&exit_code] { exit_code = vobench::exec_cell(work_dir); });
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const std::exception& e) {
        spdlog::error("{}", e.what());
        return 1;
    }
    return exit_code;
}
