// vobench-worker — the two commands that need OpenCV and TBB: rendering (`synth`) and a cell's child
// (`cell-exec`, which caps the threads OpenCV and TBB may use inside the cell). `vobench` forwards
// these commands here (execv), so that every other command — eval, traj, plugins, run, report —
// starts without loading OpenCV, GDAL and TBB. Not meant to be called by hand.
#include "cli/app_setup.hpp"
#include "cli/commands.hpp"
#include "sweep/cell_runner.hpp"
#include "util/frame_memory.hpp"

int main(int argc, char** argv) {
    vobench::keep_frame_buffers_allocated();  // both commands handle frame after frame
    CLI::App app{"vobench-worker — vobench's rendering and cell processes (run through vobench)"};
    app.require_subcommand(1, 1);
    vobench::cli::setup_logging(app);
    int exit_code = 0;
    vobench::cli::add_synth_command(app, exit_code);
    auto* exec = app.add_subcommand("cell-exec", "The child process of one cell (see sweep/cell_runner.hpp)");
    static std::string work_dir;
    exec->add_option("work_dir", work_dir)->required();
    exec->callback([&exit_code] { exit_code = vobench::exec_cell(work_dir); });
    return vobench::cli::parse_and_run(app, argc, argv, exit_code);
}
