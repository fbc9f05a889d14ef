// sweep_run.hpp — `vobench run` below the report: the output folder checked (prepare_output), the
// sweep's record written (sweep.json, cells.json, as record/results_dir.hpp lays them out), and the
// cells run by the chosen backend. The caller holds the folder's lock and writes the report after.
#pragma once

#include "sweep/local_scheduler.hpp"
#include "sweep/slurm_backend.hpp"
#include "sweep/sweep_config.hpp"

#include <string>
#include <vector>

namespace vobench {

struct SweepRunOptions {
    SweepOptions sweep;
    std::string backend = "local";  // "local" or "slurm"
    SlurmOptions slurm;
    bool detach = false;  // slurm: return once submitted
};

struct SweepRun {
    SweepTally tally;
    std::string slurm_job;  // the submitted job (slurm)
    bool detached = false;  // submitted and not followed: `vobench collect` finishes it
};

// Throws std::runtime_error (with the remedy) when the folder cannot take this sweep, and what the
// backends throw; never for anything a plugin or cell does.
SweepRun run_sweep(const SweepConfig& config, const std::vector<Cell>& cells, const SweepRunOptions& options);

}  // namespace vobench
