#include "record/run_record.hpp"

#include "metrics/metric_catalog.hpp"
#include "metrics/trajectory_io.hpp"
#include "record/host_info.hpp"
#include "record/results_dir.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <tuple>

namespace vobench {
namespace fs = std::filesystem;

std::optional<metrics::Evaluation> evaluate_run(const fs::path& dir, const metrics::Protocol& protocol, std::string& error) {
    try {
        if (!fs::exists(dir / "groundtruth.txt"))
            throw std::runtime_error("no ground truth was saved (the run stopped before the sequence opened)");
        const metrics::Trajectory gt = metrics::read_trajectory(dir / "groundtruth.txt").poses;
        const metrics::Trajectory est = metrics::read_trajectory(dir / "trajectory.txt").poses;
        if (gt.empty()) throw std::runtime_error("the sequence has no ground truth");
        if (est.size() < 2) throw std::runtime_error("fewer than two estimated poses");
        return metrics::evaluate(gt, est, protocol);
    } catch (const std::exception& e) {
        error = e.what();
        return std::nullopt;
    }
}

MetricMap evaluate_run_files(const fs::path& dir, const metrics::Protocol& protocol, std::string& error, nlohmann::json* full) {
    const auto e = evaluate_run(dir, protocol, error);
    if (!e) return {};
    if (full) *full = metrics::evaluation_json(*e);
    return metrics::flatten(*e);
}

namespace {

// Why an "ok" record's stored metrics are not usable, or "": a value that is not a finite number, a
// name outside the catalogue, or (where `recomputed` is given) a value its trajectory does not give.
std::string stored_metrics_problem(const RunRecord& r, const MetricMap* recomputed) {
    const nlohmann::json stored = r.run.value("metrics", nlohmann::json::object());
    if (!stored.is_object()) return "run.json's metrics are not an object";
    for (const auto& [name, v] : stored.items()) {
        if (!metrics::find_metric(name)) return "run.json names an unknown metric '" + clean_text(name) + "'";
        if (!v.is_number() || !std::isfinite(v.get<double>())) return "the metric " + name + " is not a finite number";
        if (!recomputed) continue;
        const auto it = recomputed->find(name);
        if (it == recomputed->end()) return "run.json has " + name + ", its trajectory gives none";
        if (std::abs(v.get<double>() - it->second) > 1e-9 * std::max(1.0, std::abs(it->second)))
            return fmt::format("run.json says {} = {}, its trajectory gives {:.17g}", name, v.dump(), it->second);
    }
    if (recomputed)
        for (const auto& [name, value] : *recomputed)
            if (!stored.contains(name)) return "its trajectory gives " + name + ", run.json has none";
    return "";
}

}  // namespace

void write_run_record(const fs::path& dir, const RunRecordFields& f) {
    const nlohmann::json run{
        {"schema_version", 1},
        {"cell", cell_to_json(f.cell)},
        {"status", f.ok ? "ok" : "failed"},
        {"reason", f.reason},
        {"failed_at_frame", f.ok ? nlohmann::json(nullptr) : nlohmann::json(f.frames)},
        {"partial", !f.ok && f.frames > 0},
        {"frames", f.frames},
        {"frames_expected", f.frames_expected},
        {"lost_frames", f.lost_frames},
        {"dropped_frames", f.dropped_frames},
        {"plugin", f.plugin},
        {"sequence", f.sequence},
        {"host", host_info()},
        {"started", f.started},
        {"finished", f.finished},
        {"child", {{"outcome", f.child_outcome}, {"log", "child.log"}, {"processes_left_behind", f.processes_left_behind}}},
        {"timing", f.timing},
        {"timing_protocol", f.timing_protocol},
        {"metrics", f.ok ? nlohmann::json(f.metrics) : nlohmann::json::object()},
        {"evaluation", f.evaluation}};
    write_json_atomic(dir / "run.json", run);
}

std::vector<RunRecord> load_runs(const fs::path& out, std::vector<std::string>* problems, LoadOptions options) {
    std::vector<RunRecord> records;
    const ResultsDir dir(out);
    const auto problem = [&](const std::string& text) {
        spdlog::warn("{}", text);
        if (problems) problems->push_back(text);
    };
    std::set<std::string> present;
    for (const std::string& id : dir.run_ids()) {
        const fs::path run_dir = dir.run_dir(id);
        present.insert(id);
        if (const std::string why = record_problem(run_dir, id); !why.empty()) {
            problem(id + ": not shown, " + why + " (" + run_dir.string() + ")");
            continue;
        }
        const fs::path file = run_dir / "run.json";
        try {
            RunRecord r;
            r.dir = run_dir;
            r.run = read_json_or_null(file, std::uintmax_t{64} << 20);
            r.cell = cell_from_json(r.run.at("cell"));
            r.ok = r.run.at("status") == "ok";
            r.reason = r.run.value("reason", "");
            r.partial = r.run.value("partial", false);
            // Undeclared in the config: the reader's declaration (when it made one).
            const nlohmann::json seq = r.run.value("sequence", nlohmann::json::object());
            if (r.cell.gt_accuracy.position_m < 0) r.cell.gt_accuracy.position_m = seq.value("gt_position_sigma_m", -1.0);
            if (r.cell.gt_accuracy.rotation_deg < 0) r.cell.gt_accuracy.rotation_deg = seq.value("gt_rotation_sigma_deg", -1.0);
            // The numbers are run.json's (a failed row stores none: it ranks nothing); trajectories
            // are evaluated again below, after sorting.
            const nlohmann::json stored = r.run.value("metrics", nlohmann::json::object());  // named: items() must not outlive it
            if (r.ok && stored.is_object())
                for (const auto& [name, v] : stored.items())
                    if (metrics::find_metric(name) && v.is_number()) r.metrics[name] = v.get<double>();
            const nlohmann::json& t = r.run.at("timing");
            if (t.value("frames", 0) > 0) {
                r.metrics["ms_per_frame"] = t.at("mean_ms");
                r.metrics["fps"] = t.at("fps");
            }
            if (t.contains("dropped_frames") && t["dropped_frames"].is_number()) r.metrics["dropped_frames"] = t["dropped_frames"];
            const double lost = r.run.value("lost_frames", 0.0);
            const double missing = std::max(0.0, r.run.value("frames_expected", 0.0) - r.run.value("frames", 0.0));
            r.metrics["lost_frames"] = lost;
            r.metrics["failed_frames"] = lost + (r.ok ? 0.0 : missing);
            // JSON may hold 1e400 (parsed as infinity): a shown number is finite.
            for (auto it = r.metrics.begin(); it != r.metrics.end();) it = std::isfinite(it->second) ? std::next(it) : r.metrics.erase(it);
            if (r.ok && !options.re_evaluate)
                if (const std::string why = stored_metrics_problem(r, nullptr); !why.empty()) {
                    problem(id + ": not shown, " + why + " (" + run_dir.string() + ")");
                    continue;
                }
            records.push_back(std::move(r));
        } catch (const std::exception& e) {
            problem(id + ": not shown, run.json is not a readable run record: " + clean_text(e.what()) + " (" + run_dir.string() + ")");
        }
    }
    for (const std::string& id : dir.expected_ids())
        if (!present.count(id)) problem(id + ": missing (in cells.json, no record under runs/)");
    std::sort(records.begin(), records.end(), [](const RunRecord& a, const RunRecord& b) {
        return std::tie(a.cell.dataset, a.cell.sequence, a.cell.sensor, a.cell.algorithm, a.cell.params, a.cell.repeat) <
               std::tie(b.cell.dataset, b.cell.sequence, b.cell.sensor, b.cell.algorithm, b.cell.params, b.cell.repeat);
    });
    // Trajectories evaluated again: the figure cell of each entry × sequence × sensor (the first
    // successful one in this order), its stored metrics checked against what it gives; or, with
    // re_evaluate, every cell, whose metrics then replace the stored ones.
    std::set<std::string> drawn;
    std::vector<RunRecord> kept;
    for (RunRecord& r : records) {
        const std::string group = r.cell.entry_label() + '\x1f' + r.cell.dataset + '\x1f' + r.cell.sequence + '\x1f' + r.cell.sensor;
        if (!options.re_evaluate && !(r.ok && drawn.insert(group).second)) {
            kept.push_back(std::move(r));
            continue;
        }
        r.evaluation = evaluate_run(r.dir, r.cell.protocol, r.evaluation_error);
        MetricMap recomputed;
        if (r.evaluation) recomputed = metrics::flatten(*r.evaluation);
        if (options.re_evaluate) {
            for (const auto& [name, value] : recomputed)
                if (std::isfinite(value)) r.metrics[name] = value;
        } else if (const std::string why = stored_metrics_problem(r, &recomputed); !why.empty()) {
            problem(r.cell.id + ": not shown, " + why + " (" + r.dir.string() + ")");
            drawn.erase(group);  // the next successful cell of the group draws its figure
            continue;
        }
        kept.push_back(std::move(r));
    }
    return kept;
}

}  // namespace vobench
