// cell_runner.hpp — one cell, isolated.
//
// The supervisor (run_cell) prepares runs/.work/<id>/, starts `vobench cell-exec <that folder>` as a
// child process under the cell's timeout and memory limit, and waits. The child streams every frame
// (pose, process time, stages, counters) to frames.jsonl as it goes, so that whatever ends it — a
// signal, abort(), exit(), the timeout, the memory limit, a non-finite pose, a plugin error — the
// frames before are kept. The supervisor then turns the stream into trajectory.txt and timing.csv,
// evaluates against the ground truth the child saved, writes run.json, and moves the folder to
// runs/<id>/ with one rename: a cell folder exists complete or not at all.
#pragma once

#include "sweep/cell.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <filesystem>
#include <string>

namespace vobench {

struct CellOutcome {
    std::string id;
    bool ok = false;
    std::string reason;   // why it failed ("" when ok)
    uint64_t frames = 0;  // frames processed
    double wall_s = 0;
    bool interrupted = false;  // stopped by the user: nothing was recorded, the cell is still to do
};

// Runs one cell and writes <out>/runs/<id>/. Never throws for anything the plugin or data does;
// throws std::runtime_error only when the output folder cannot be written.
// `cancel` (optional): when it becomes true the cell's child is killed and nothing is recorded.
// `pinned_core` >= 0: the cell's processes run on that CPU only (sched_setaffinity), as `run -j N`
// does with N cells on N cores, so that two cells never share a core; -1: not pinned.
CellOutcome run_cell(const Cell& cell, const std::filesystem::path& out, const std::atomic<bool>* cancel = nullptr, int pinned_core = -1);

// The failed row of a cell that never ran (e.g. its Slurm array task was cancelled or timed out):
// runs/<id>/ with run.json giving `reason`, written the same atomic way.
CellOutcome record_unrun_cell(const Cell& cell, const std::filesystem::path& out, const std::string& reason);

// The child side (`vobench cell-exec WORKDIR`, sweep/cell_child.cpp): reads WORKDIR/cell.json, runs
// the track, streams frames.jsonl and writes result.json. Returns the process exit code (0 when
// result.json was written).
int exec_cell(const std::filesystem::path& work_dir);

// True when <out>/runs/<id>/ holds a sound record (record_problem() finds nothing), successful or not.
bool cell_finished(const std::filesystem::path& out, const std::string& id);

}  // namespace vobench
