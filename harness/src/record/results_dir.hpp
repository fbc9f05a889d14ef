// results_dir.hpp — the layout of a sweep's output folder, the one contract between sweep, report,
// Slurm and collect, and the one test of "is this cell finished".
//
//   OUT/runs/<id>/         a finished cell (run.json written last, the folder moved in by one rename)
//   OUT/runs/.work/<id>/   a cell being run (never trusted: redone)
//   OUT/stale/<id>/        finished cells of another config or plugin build (--resume moves them)
//   OUT/corrupt/<id>.<time>/  records that failed validation, set aside (--resume re-runs the cell)
//   OUT/cells.json, OUT/sweep.json, OUT/.vobench.lock
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

class ResultsDir {
public:
    explicit ResultsDir(std::filesystem::path root) : root_(std::move(root)) {}
    const std::filesystem::path& root() const { return root_; }
    std::filesystem::path runs() const { return root_ / "runs"; }
    std::filesystem::path run_dir(const std::string& id) const { return runs() / id; }
    std::filesystem::path work_dir(const std::string& id) const { return runs() / ".work" / id; }
    std::filesystem::path stale() const { return root_ / "stale"; }
    std::filesystem::path corrupt() const { return root_ / "corrupt"; }
    std::filesystem::path cells_json() const { return root_ / "cells.json"; }
    std::filesystem::path sweep_json() const { return root_ / "sweep.json"; }
    std::filesystem::path lock_file() const { return root_ / ".vobench.lock"; }

    // Folders under runs/ (not .work), sorted; whether their records are sound is not checked.
    std::vector<std::string> run_ids() const;
    // The ids of cells.json, in its order; empty when it is missing or unreadable.
    std::vector<std::string> expected_ids() const;

private:
    std::filesystem::path root_;
};

// Why runs/<id>/ is not a sound record, or "" when it is: run.json parses and is an object with
// schema_version 1, names this id, has status "ok" or "failed" and an integer frame count, and its
// trajectory.txt holds exactly that many poses.
std::string record_problem(const std::filesystem::path& run_dir, const std::string& id);

// Moves runs/<id>/ to corrupt/<id>.<time>/ so the cell is run again and the evidence kept.
std::filesystem::path set_aside_corrupt(const ResultsDir& dir, const std::string& id);

}  // namespace vobench
