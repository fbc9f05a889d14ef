// local_scheduler.hpp — the sweep on this machine: a pool of `jobs` workers, each running one cell
// at a time in its own child process (cell_runner). Finished cells (runs/<id>/run.json) are skipped
// with --resume; the sweep always finishes, whatever the plugins do.
#pragma once

#include "sweep/cell.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

struct SweepOptions {
    std::filesystem::path out;
    int jobs = 1;
    bool resume = false;
    bool fresh = false;  // discard earlier results in `out` (moved to out/discarded-<time>/)
    std::string only;    // wildcard on dataset/sequence/sensor/algorithm/id
};

struct SweepTally {
    std::size_t cells = 0, skipped = 0, ran = 0, failed = 0;
    uint64_t frames = 0;
    double wall_s = 0;
    bool interrupted = false;  // SIGINT/SIGTERM: running cells were stopped and not recorded
};

// Checks `out` against the options before anything runs: refuses to mix a new sweep into earlier
// results unless --resume or --fresh; with --resume, moves finished cells that are not in `cells`
// (another config or plugin build) to out/stale/ so the report shows only this sweep.
// Throws std::runtime_error with the remedy.
void prepare_output(const std::vector<Cell>& cells, const SweepOptions& options);

// The cells to run (after --only and --resume).
std::vector<Cell> pending_cells(const std::vector<Cell>& cells, const SweepOptions& options);

// SIGINT or SIGTERM (Ctrl-C) stops the sweep: no new cell starts, running cells are killed and left
// unrecorded (to be redone by --resume), finished ones are kept; the tally says `interrupted`.
SweepTally run_local(const std::vector<Cell>& cells, const SweepOptions& options);

}  // namespace vobench
