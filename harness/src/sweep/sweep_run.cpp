#include "sweep/sweep_run.hpp"

#include "record/results_dir.hpp"
#include "util/files.hpp"

#include <spdlog/spdlog.h>

namespace vobench {

SweepRun run_sweep(const SweepConfig& config, const std::vector<Cell>& cells, const SweepRunOptions& options) {
    const SweepOptions& o = options.sweep;
    const ResultsDir dir(o.out);
    prepare_output(cells, o);
    write_json_atomic(dir.sweep_json(), sweep_record(config));
    nlohmann::json list = nlohmann::json::array();
    for (const Cell& c : cells) list.push_back(cell_to_json(c));
    write_file_atomic(dir.cells_json(), json_text(list, 1) + "\n");
    SweepRun run;
    if (options.backend == "slurm") {
        spdlog::info("{}: {} cells on Slurm, output {}", config.file.string(), cells.size(), o.out.string());
        run.slurm_job = submit_slurm(pending_cells(cells, o), o.out, options.slurm, config.limits.threads);
        if (run.slurm_job.empty()) spdlog::info("every cell is finished; nothing to submit");
        if (options.detach) {
            run.detached = true;
            return run;
        }
        run.tally = follow_slurm(o.out, options.slurm.poll_s);
    } else {
        spdlog::info("{}: {} cells, -j {}, output {}", config.file.string(), cells.size(), o.jobs, o.out.string());
        run.tally = run_local(cells, o);
    }
    return run;
}

}  // namespace vobench
