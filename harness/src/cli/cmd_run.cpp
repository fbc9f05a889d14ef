// vobench run / report / collect / run-cell — sweeps from a YAML config, isolated cells, and the report.
#include "cli/commands.hpp"
#include "metrics/trajectory_io.hpp"
#include "report/report_writer.hpp"
#include "sweep/cell_runner.hpp"
#include "sweep/local_scheduler.hpp"
#include "sweep/sequence_probe.hpp"
#include "sweep/slurm_backend.hpp"
#include "sweep/sweep_run.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"
#include "util/folder_lock.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <iostream>

namespace vobench::cli {
namespace fs = std::filesystem;

namespace {

void print_report(const ReportResult& r, const fs::path& out) {
    std::cout << "\n## Kinect v1 vs v2 — accuracy in the layout of Table 5 (Kraft et al. 2016)\n\n"
              << r.accuracy_markdown << fmt::format("{} cells, {} failed.\n", r.runs, r.failed)
              << "Report: " << (out / "report.html").string() << "\nTables: " << (out / "summary.md").string()
              << ", summary.csv, summary.tex; "
              << "leaderboard: " << (out / "leaderboard.json").string() << "\n";
    for (const std::string& f : r.failed_required) std::cout << "REQUIRED CRITERION NOT MET: " << f << "\n";
    if (!r.problems.empty()) {
        std::cout << "INCOMPLETE: " << r.problems.size() << " cells missing or unsound:\n";
        for (const std::string& p : r.problems) std::cout << "  " << clean_text(p) << "\n";
    }
}

// 0: complete and every required criterion met; 1: a required criterion failed; 2: cells are missing
// or their records unsound (the report says which).
int report_status(const ReportResult& r, bool complete_expected) {
    if (complete_expected && !r.problems.empty()) return 2;
    return r.failed_required.empty() ? 0 : 1;
}

}  // namespace

void add_run_commands(CLI::App& app, int& exit_code) {
    auto* run = app.add_subcommand("run", "Run a sweep from a YAML config: every cell in its own process, then the report");
    static std::string config_file, out, only, backend;
    static int jobs = 1;
    static bool resume = false, fresh = false, dry_run = false, detach = false;
    static SlurmOptions slurm;
    run->add_option("config", config_file, "Sweep configuration (YAML); see configs/README.md")->required();
    run->add_option("--out", out, "Output folder (default: the config's output:)");
    run->add_option("-j,--jobs", jobs, "Cells run at once (each one process)")->check(CLI::Range(1, 1024))->capture_default_str();
    run->add_flag("--resume", resume, "Skip finished cells (after an interruption, or to add cells)");
    run->add_flag("--fresh", fresh, "Set earlier results in the output folder aside and start again");
    run->add_option("--only", only, "Run only cells whose dataset/sequence/sensor/algorithm/id matches this wildcard");
    run->add_flag("--dry-run", dry_run, "Validate and list the cells; run and render nothing");
    run->add_option("--backend", backend, "local or slurm (default: the config's backend:, else local)")
        ->check(CLI::IsMember({"local", "slurm"}));
    run->add_option("--partition", slurm.partition, "slurm: sbatch --partition")->group("Slurm");
    run->add_option("--account", slurm.account, "slurm: sbatch --account")->group("Slurm");
    run->add_option("--time", slurm.time, "slurm: sbatch --time per array task, e.g. 2:00:00")->group("Slurm");
    run->add_option("--mem", slurm.mem, "slurm: sbatch --mem per array task, e.g. 8G")->group("Slurm");
    run->add_option("--array-limit", slurm.array_limit, "slurm: at most K array tasks at once")->group("Slurm");
    run->add_option("--chunk", slurm.chunk, "slurm: cells per array task")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str()
        ->group("Slurm");
    run->add_option("--poll", slurm.poll_s, "slurm: seconds between squeue calls")
        ->check(CLI::Range(1, 3600))
        ->capture_default_str()
        ->group("Slurm");
    run->add_flag("--detach", detach, "slurm: return after submitting; `vobench collect DIR` finishes")->group("Slurm");
    run->callback([&exit_code] {
        const PluginRegistry registry;
        const SweepConfig config = load_sweep_config(config_file, registry, !dry_run);
        SweepOptions o;
        o.out = out.empty() ? config.output : fs::path(out);
        o.jobs = jobs;
        o.resume = resume;
        o.fresh = fresh;
        o.only = only;
        const std::vector<Cell> cells = expand_cells(config, registry, o.out, !dry_run);
        if (dry_run) {
            std::size_t selected = 0;
            for (const Cell& c : cells) {
                if (!only.empty() && !cell_matches(c, only)) continue;
                ++selected;
                std::cout << fmt::format("{}  {}/{}/{}  {}  seed {}{}\n", c.id, c.dataset, c.sequence, c.sensor.empty() ? "-" : c.sensor,
                                         c.entry_label(), c.seed, c.load_error.empty() ? "" : "  (plugin refuses to load: will fail)");
            }
            std::cout << fmt::format("{} cells ({} selected); output {}\n", cells.size(), selected, o.out.string());
            exit_code = 0;
            return;
        }
        SweepRunOptions ro;
        ro.sweep = o;
        ro.backend = backend.empty() ? config.backend : backend;
        ro.slurm = slurm;
        ro.detach = detach;
        const FolderLock lock(o.out);  // one writer per folder, until the report is written
        const SweepRun sweep = run_sweep(config, cells, ro);
        if (sweep.detached) {
            std::cout << fmt::format("Submitted Slurm job {}. When it ends: vobench collect {}\n", sweep.slurm_job, o.out.string());
            exit_code = 0;
            return;
        }
        const SweepTally& t = sweep.tally;
        if (t.interrupted) {
            spdlog::warn(
                "interrupted: {} cells finished and kept, the running ones discarded; continue with: vobench run {} --out {} --resume",
                t.ran, config_file, o.out.string());
            exit_code = 130;
            return;
        }
        spdlog::info("sweep finished: {} cells run ({} failed), {} skipped, {} frames in {:.1f} s", t.ran, t.failed, t.skipped, t.frames,
                     t.wall_s);
        const ReportResult r = write_report(o.out);
        print_report(r, o.out);
        exit_code = report_status(r, only.empty());
    });

    auto* report = app.add_subcommand("report", "Rebuild tables, leaderboard, figures and report.html from DIR/runs alone");
    static std::string report_dir;
    static bool re_evaluate = false;
    report->add_option("dir", report_dir, "A sweep's output folder")->required()->check(CLI::ExistingDirectory);
    report->add_flag("--re-evaluate", re_evaluate,
                     "Recompute every cell's metrics from its trajectory (default: run.json's, checked where a figure is drawn)");
    report->callback([&exit_code] {
        const FolderLock lock(report_dir);
        const ReportResult r = write_report(report_dir, re_evaluate);
        print_report(r, report_dir);
        exit_code = report_status(r, true);
    });

    auto* collect = app.add_subcommand("collect", "Follow a detached Slurm sweep in DIR to its end, record failed tasks, write the report");
    static std::string collect_dir;
    static int collect_poll = 5;
    collect->add_option("dir", collect_dir, "The sweep's output folder")->required()->check(CLI::ExistingDirectory);
    collect->add_option("--poll", collect_poll, "Seconds between squeue calls")->capture_default_str();
    collect->callback([&exit_code] {
        const FolderLock lock(collect_dir);
        const SweepTally t = follow_slurm(collect_dir, collect_poll);
        spdlog::info("collected: {} cells ({} failed)", t.cells, t.failed);
        const ReportResult r = write_report(collect_dir);
        print_report(r, collect_dir);
        exit_code = report_status(r, true);
    });

    // Internal: one Slurm array task (see sweep/slurm_backend.hpp).
    auto* batch = app.add_subcommand("run-cell", "Run cells of a sweep's batch file (what a Slurm array task does)")->group("");
    static std::string batch_out, batch_file;
    static int batch_task = 0, batch_chunk = 1;
    batch->add_option("out", batch_out)->required();
    batch->add_option("--batch", batch_file)->required();
    batch->add_option("--task", batch_task)->required();
    batch->add_option("--chunk", batch_chunk)->required();
    batch->callback([&exit_code] { exit_code = run_cell_batch(batch_out, batch_file, batch_task, batch_chunk); });

    // Internal: a sequence's frame count from its reader alone (see sweep/sequence_probe.hpp).
    auto* seq_probe = app.add_subcommand("sequence-probe", "")->group("");
    static std::string probe_reader, probe_path, probe_options, probe_result;
    seq_probe->add_option("reader", probe_reader)->required();
    seq_probe->add_option("path", probe_path)->required();
    seq_probe->add_option("options", probe_options)->required();
    seq_probe->add_option("result", probe_result)->required();
    seq_probe->callback([&exit_code] { exit_code = sequence_probe_main(probe_reader, probe_path, probe_options, probe_result); });

    // Internal: the child process of one cell runs in vobench-worker (cli/worker_main.cpp).
}

}  // namespace vobench::cli
