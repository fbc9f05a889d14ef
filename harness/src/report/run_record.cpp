#include "report/run_record.hpp"

#include "metrics/trajectory_io.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <tuple>

namespace vobench {
namespace fs = std::filesystem;

std::optional<metrics::Evaluation> evaluate_run(const fs::path& dir, const metrics::Protocol& protocol, std::string& error) {
    try {
        if (!fs::exists(dir / "groundtruth.txt")) throw std::runtime_error("no ground truth was saved (the run stopped before the sequence opened)");
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

MetricMap flatten(const metrics::Evaluation& e) {
    MetricMap m;
    if (e.ate) {
        const auto& s = e.ate->stats;
        m["ate.rmse"] = s.rmse;
        m["ate.mean"] = s.mean;
        m["ate.median"] = s.median;
        m["ate.std"] = s.std;
        m["ate.max"] = s.max;
    }
    if (e.rpe) {
        m["rpe.trans.rmse"] = e.rpe->trans.rmse;
        m["rpe.trans.mean"] = e.rpe->trans.mean;
        m["rpe.trans.median"] = e.rpe->trans.median;
        m["rpe.rot.rmse"] = e.rpe->rot_deg.rmse;
        m["rpe.rot.mean"] = e.rpe->rot_deg.mean;
        m["rpe.rot.median"] = e.rpe->rot_deg.median;
    }
    return m;
}

MetricMap evaluate_run_files(const fs::path& dir, const metrics::Protocol& protocol, std::string& error, nlohmann::json* full) {
    const auto e = evaluate_run(dir, protocol, error);
    if (!e) return {};
    if (full) *full = metrics::evaluation_json(*e);
    return flatten(*e);
}

std::vector<RunRecord> load_runs(const fs::path& out) {
    std::vector<RunRecord> records;
    const fs::path runs = out / "runs";
    if (!fs::is_directory(runs)) return records;
    for (const auto& entry : fs::directory_iterator(runs)) {
        if (!entry.is_directory() || entry.path().filename().string().front() == '.') continue;
        const fs::path file = entry.path() / "run.json";
        if (!fs::exists(file)) continue;  // never happens for a cell moved into place; tolerate hand-made folders
        try {
            std::ifstream in(file);
            RunRecord r;
            r.dir = entry.path();
            r.run = nlohmann::json::parse(in);
            r.cell = cell_from_json(r.run.at("cell"));
            r.ok = r.run.at("status") == "ok";
            r.reason = r.run.value("reason", "");
            r.partial = r.run.value("partial", false);
            // Undeclared in the config: the reader's declaration (when it made one).
            const nlohmann::json seq = r.run.value("sequence", nlohmann::json::object());
            if (r.cell.gt_accuracy.position_m < 0) r.cell.gt_accuracy.position_m = seq.value("gt_position_sigma_m", -1.0);
            if (r.cell.gt_accuracy.rotation_deg < 0) r.cell.gt_accuracy.rotation_deg = seq.value("gt_rotation_sigma_deg", -1.0);
            r.evaluation = evaluate_run(r.dir, r.cell.protocol, r.evaluation_error);
            if (r.evaluation) r.metrics = flatten(*r.evaluation);
            const nlohmann::json& t = r.run.at("timing");
            if (t.value("frames", 0) > 0) {
                r.metrics["ms_per_frame"] = t.at("mean_ms");
                r.metrics["fps"] = t.at("fps");
            }
            const double lost = r.run.value("lost_frames", 0.0);
            const double missing = std::max(0.0, r.run.value("frames_expected", 0.0) - r.run.value("frames", 0.0));
            r.metrics["lost_frames"] = lost;
            r.metrics["failed_frames"] = lost + (r.ok ? 0.0 : missing);
            records.push_back(std::move(r));
        } catch (const std::exception& e) {
            spdlog::warn("{}: skipped, not a readable run record: {}", file.string(), e.what());
        }
    }
    std::sort(records.begin(), records.end(), [](const RunRecord& a, const RunRecord& b) {
        return std::tie(a.cell.dataset, a.cell.sequence, a.cell.sensor, a.cell.algorithm, a.cell.params, a.cell.repeat) <
               std::tie(b.cell.dataset, b.cell.sequence, b.cell.sensor, b.cell.algorithm, b.cell.params, b.cell.repeat);
    });
    return records;
}

}  // namespace vobench
