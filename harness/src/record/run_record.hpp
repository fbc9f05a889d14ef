// run_record.hpp — a finished cell as the report reads it back: runs/<id>/run.json plus the metrics,
// recomputed from runs/<id>/trajectory.txt and groundtruth.txt with the protocol the cell recorded.
// Everything the tables, leaderboard, figures and page show comes from these records alone.
#pragma once

#include "metrics/evaluation.hpp"
#include "metrics/metric_catalog.hpp"
#include "record/cell.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vobench {

using metrics::MetricMap;  // by catalogue name (metrics/metric_catalog.hpp)

struct RunRecord {
    std::filesystem::path dir;
    Cell cell;
    nlohmann::json run;  // run.json as written
    bool ok = false;
    std::string reason;                             // failure reason
    bool partial = false;                           // stopped early: trajectory holds the frames before the failure
    MetricMap metrics;                              // accuracy (run.json's, unless re-evaluated) and timing
    std::optional<metrics::Evaluation> evaluation;  // per-pair errors, for the figures (see LoadOptions)
    std::string evaluation_error;
    // Identity of the table entry this run belongs to (algorithm + parameters).
    std::string entry() const { return cell.entry_label(); }
};

// ATE/RPE of `dir`/trajectory.txt against `dir`/groundtruth.txt. On failure returns nullopt and
// sets `error`.
std::optional<metrics::Evaluation> evaluate_run(const std::filesystem::path& dir, const metrics::Protocol& protocol, std::string& error);

// Both of the above: the flat metrics ({} on failure), `full` (optional) the evaluation JSON.
MetricMap evaluate_run_files(const std::filesystem::path& dir, const metrics::Protocol& protocol, std::string& error,
                             nlohmann::json* full = nullptr);

// Everything a finished cell's record holds, as the supervisor established it.
struct RunRecordFields {
    Cell cell;
    bool ok = false;
    std::string reason;            // "" when ok
    uint64_t frames = 0;           // poses recorded
    uint64_t frames_expected = 0;  // what the reader declared (capped by the cell's frame limit)
    uint64_t lost_frames = 0;
    uint64_t dropped_frames = 0;  // real-time mode: handled (in `frames`), not given to the plugin, no pose
    nlohmann::json plugin = nlohmann::json::object(), sequence = nlohmann::json::object();
    std::string started, finished;
    std::string child_outcome;  // "exited with code 0", "not started", …
    std::size_t processes_left_behind = 0;
    nlohmann::json timing = nlohmann::json::object();
    nlohmann::json timing_protocol = nlohmann::json::object();  // record/timing_stats.hpp timing_protocol
    MetricMap metrics;                                          // kept only when ok: a failed row ranks nothing
    nlohmann::json evaluation;                                  // evaluation_json, or {"error": …}
};

// Writes `dir`/run.json (schemas/run.schema.json) atomically; the reading side is load_runs() below
// and record_problem() (record/results_dir.hpp). Throws std::runtime_error when it cannot be written.
void write_run_record(const std::filesystem::path& dir, const RunRecordFields& fields);

struct LoadOptions {
    // false (default): the metrics are run.json's, the one source of the numbers; a trajectory is
    // evaluated again only where a figure needs its per-pair errors (the first successful cell of
    // each entry × sequence × sensor), and those cells' stored metrics must equal what it gives.
    // true (`vobench report --re-evaluate`, after changing a protocol): every cell is evaluated again
    // with its recorded protocol, and those metrics are reported.
    bool re_evaluate = false;
};

// Every sound record under `out`/runs in the expansion order (dataset, sequence, sensor, algorithm,
// variant, repeat). A record that is not sound (record_problem(), an unreadable cell, an "ok" record
// whose stored metrics are not finite or differ from what its trajectory gives where it is evaluated
// again) is left out and named in `problems`, as is every cell of cells.json that has no record.
// Never throws for a record.
std::vector<RunRecord> load_runs(const std::filesystem::path& out, std::vector<std::string>* problems = nullptr, LoadOptions options = {});

}  // namespace vobench
