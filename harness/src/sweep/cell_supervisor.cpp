// cell_supervisor.cpp — the supervising side of one cell: prepares runs/.work/<id>/, runs the child
// under the cell's limits, verifies everything it left and writes runs/<id>/ with one rename.
//
// The supervisor believes nothing it did not check. A cell is `ok` only when the child exited 0, said
// "ok", the frame stream parses to one finite pose per frame the reader declared (no more, no fewer),
// no process of the cell outlived it, and every metric is finite. Anything else is a failed row with
// the reason and the frame (and the trajectory up to it, marked partial).
#include "metrics/statistics.hpp"
#include "record/frame_stream.hpp"
#include "record/host_info.hpp"
#include "record/results_dir.hpp"
#include "record/run_record.hpp"
#include "record/timing_stats.hpp"
#include "sweep/cell_runner.hpp"
#include "track/track.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"
#include "util/subprocess.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

namespace vobench {
namespace fs = std::filesystem;

namespace {

// Per-frame times of the plugin's process() call only (record/timing_stats.hpp: after the warm-up
// frames, dropped frames counted, not timed), and what the child and its loop cost around it.
nlohmann::json timing_summary(const FrameStream& r, const nlohmann::json& result, const ChildResult& child, const TimingSpec& spec) {
    nlohmann::json j = timing_statistics(r.frames, spec);
    double timed_ns = 0, read_ns = 0;
    for (const FrameRecord& f : r.frames) {
        timed_ns += static_cast<double>(f.process_ns);
        read_ns += static_cast<double>(f.read_ns);
    }
    const double n = static_cast<double>(std::max<std::size_t>(1, r.frames.size()));
    const auto number = [&](const char* key) {
        return result.is_object() && result.contains(key) && result[key].is_number() ? result[key].get<double>() : 0.0;
    };
    j["frames"] = j["frames_timed"];
    j["timed_s"] = timed_ns * 1e-9;
    j["read_s"] = read_ns * 1e-9;
    j["read_ms_per_frame"] = read_ns * 1e-6 / n;
    j["child_wall_s"] = child.wall_s;
    j["peak_rss_mb"] = std::max(static_cast<double>(child.peak_rss_kb), number("peak_rss_kb")) / 1024.0;
    const double loop_wall_s = number("loop_wall_ns") * 1e-9;
    if (loop_wall_s > 0) {
        j["loop_wall_s"] = loop_wall_s;
        // What the harness costs around the plugin beyond reading frames: hand-over, streaming, bookkeeping.
        const double overhead = loop_wall_s - timed_ns * 1e-9 - read_ns * 1e-9;
        j["harness_overhead_s"] = overhead;
        j["harness_overhead_pct"] = 100.0 * overhead / loop_wall_s;
    }
    return j;
}

void keep_log_tail(const fs::path& log, std::size_t max_bytes) {
    std::error_code ec;
    const auto size = fs::file_size(log, ec);
    if (ec || size <= max_bytes) return;
    std::ifstream in(log, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(size - max_bytes));
    std::string tail(max_bytes, '\0');
    in.read(tail.data(), static_cast<std::streamsize>(max_bytes));
    write_file_atomic(log, fmt::format("[… {} bytes cut …]\n", size - max_bytes) + tail);
}

// The child's own word on how it ended, if result.json is well-formed: {status, error}.
struct ChildReport {
    bool present = false;
    std::string status, error;
};

ChildReport child_report(const nlohmann::json& result) {
    ChildReport r;
    if (!result.is_object() || !result.contains("status") || !result["status"].is_string()) return r;
    r.present = true;
    r.status = result["status"];
    if (result.contains("error") && result["error"].is_string()) r.error = result["error"];
    return r;
}

uint64_t unsigned_field(const nlohmann::json& j, const char* key) {
    return j.is_object() && j.contains(key) && j[key].is_number_unsigned() ? j[key].get<uint64_t>() : 0;
}

// Only the fields the report reads, each of its type (the child's files may have been rewritten by
// plugin code): strings cleaned, numbers finite; anything else left out.
nlohmann::json well_typed(const nlohmann::json& from, const std::vector<std::pair<const char*, char>>& fields) {
    nlohmann::json out = nlohmann::json::object();
    if (!from.is_object()) return out;
    for (const auto& [key, type] : fields) {
        if (!from.contains(key)) continue;
        const nlohmann::json& v = from[key];
        if (type == 's' && v.is_string()) out[key] = clean_text(v.get<std::string>());
        if (type == 'u' && v.is_number_unsigned()) out[key] = v;
        if (type == 'n' && v.is_number() && std::isfinite(v.get<double>())) out[key] = v;
    }
    return out;
}

nlohmann::json sequence_fields(const nlohmann::json& s) {
    nlohmann::json out = well_typed(s, {{"name", 's'},
                                        {"sensor", 's'},
                                        {"frame_count", 'u'},
                                        {"frames_to_run", 'u'},
                                        {"gt_count", 'u'},
                                        {"gt_position_sigma_m", 'n'},
                                        {"gt_rotation_sigma_deg", 'n'}});
    if (s.is_object() && s.contains("camera"))
        out["camera"] = well_typed(s["camera"], {{"width", 'n'}, {"height", 'n'}, {"fx", 'n'}, {"fy", 'n'}, {"cx", 'n'}, {"cy", 'n'}});
    return out;
}

nlohmann::json plugin_fields(const nlohmann::json& p) {
    return well_typed(p, {{"name", 's'}, {"version", 's'}, {"license", 's'}, {"abi_version", 'u'}, {"api_version", 'u'}, {"file", 's'}});
}

// Why the cell is not a success, or "" when it is. Checked in the order a user would want to read.
std::string verdict(bool ran, const std::string& not_run_reason, const ChildResult& child, const ChildReport& report,
                    const FrameStream& frames, const nlohmann::json& sequence, const std::string& plugin, int64_t required) {
    const std::size_t got = frames.frames.size();
    if (!ran) return not_run_reason;
    if (child.signal_blame != 0)
        return fmt::format("a process of the cell sent {} to the harness at frame {} (cell killed)", signal_name(child.signal_blame), got);
    if (child.log_exceeded) return fmt::format("{} at frame {}", child.describe(), got);
    if (!(child.exited && child.exit_code == 0)) {
        if (report.present) return fmt::format("{} after the last frame (while shutting down)", child.describe());
        return fmt::format("{} at frame {}", child.describe(), got);
    }
    if (!report.present) return fmt::format("the cell's process exited 0 at frame {} without writing its result", got);
    if (report.status != "ok") return report.error.empty() ? "failed without a message" : report.error;
    if (!frames.error.empty()) return fmt::format("the frame stream is corrupt after frame {} ({})", got, frames.error);
    if (!sequence.is_object()) return "the cell's process reported success but never described the sequence";
    const uint64_t said = unsigned_field(sequence, "frames_to_run");
    // The count the reader gave when probed alone wins over what the cell's process wrote.
    if (required >= 0 && said != static_cast<uint64_t>(required))
        return fmt::format(
            "the cell's process said the sequence has {} frames to run, its reader declared {} when probed alone (files "
            "of the cell were overwritten?)",
            said, required);
    const uint64_t expected = said;
    if (expected == 0) return "the reader declared no frames";
    if (got != expected)
        return fmt::format("plugin '{}': {} of the {} frames the reader declared were recorded (the run ended early without an error)",
                           plugin, got, expected);
    if (child.left_behind > 0)
        return fmt::format("left {} process{} running after the cell ended (killed)", child.left_behind,
                           child.left_behind == 1 ? "" : "es");
    return "";
}

// Runs the cell's child unless `not_run_reason` is given, then turns whatever it left into runs/<id>/.
CellOutcome finish_cell(const Cell& cell, const fs::path& out, std::string not_run_reason, const std::atomic<bool>* cancel,
                        int pinned_core) {
    const fs::path work = out / "runs" / ".work" / cell.id;
    const fs::path final_dir = out / "runs" / cell.id;
    fs::remove_all(work);
    fs::create_directories(work);
    write_json_atomic(work / "cell.json", cell_to_json(cell));
    const std::string started = utc_now_iso();

    ChildResult child;
    bool ran = false;
    if (!cell.load_error.empty()) not_run_reason = "plugin '" + cell.plugin + "' refused to load: " + cell.load_error;
    if (not_run_reason.empty()) {
        ChildLimits limits;
        limits.timeout_s = cell.limits.timeout_s;
        limits.memory_mb = cell.limits.memory_mb;
        limits.log = work / "child.log";
        limits.cancel = cancel;
        limits.contain = true;
        limits.cpu = pinned_core;
        child = run_worker_limited({"cell-exec", work.string()}, limits);
        ran = true;
        if (child.cancelled) {  // the user stopped the sweep: not a result, the cell stays to do
            fs::remove_all(work);
            CellOutcome o;
            o.id = cell.id;
            o.interrupted = true;
            o.reason = "interrupted";
            return o;
        }
    }
    const FrameStream frames = decode_frames(work / "frames.jsonl");
    const nlohmann::json result = read_json_or_null(work / "result.json", 1 << 20);
    // Absent when the child died before the sequence opened: empty objects, never null.
    const nlohmann::json sequence_file = read_json_or_null(work / "sequence.json", 1 << 20);
    const bool described = sequence_file.is_object();
    const nlohmann::json sequence = sequence_fields(sequence_file);
    const nlohmann::json plugin = plugin_fields(read_json_or_null(work / "plugin.json", 1 << 20));

    CellOutcome o;
    o.id = cell.id;
    o.frames = frames.frames.size();
    o.reason = verdict(ran, not_run_reason, child, child_report(result), frames, described ? sequence : nlohmann::json(nullptr),
                       cell.plugin, cell.frames_required());

    TrackResult track;
    track.estimate = frames.poses;
    track.frames = frames.frames;
    track.sequence = cell.sequence;
    write_track_outputs(track, work);
    std::string evaluation_error;
    nlohmann::json evaluation;
    MetricMap metrics = evaluate_run_files(work, cell.protocol, evaluation_error, &evaluation);
    // Messages name the folder the user will find, not the work folder that is renamed away.
    for (std::size_t at; (at = evaluation_error.find(work.string())) != std::string::npos;)
        evaluation_error.replace(at, work.string().size(), final_dir.string());
    if (o.reason.empty()) {
        for (const auto& [name, value] : metrics)
            if (!std::isfinite(value)) {
                o.reason = fmt::format("the metric {} is {} (the estimate is absurd): not ranked", name, value);
                break;
            }
        const bool has_gt = unsigned_field(sequence, "gt_count") > 0;
        if (o.reason.empty() && has_gt && metrics.empty()) o.reason = "the run could not be evaluated: " + evaluation_error;
    }
    o.ok = o.reason.empty();  // a failed row keeps no metrics (below): it ranks nothing
    const nlohmann::json timing = timing_summary(frames, result, child, cell.timing);
    // The child's CPU affinity as it saw it (informational: written by the process that runs plugin code).
    nlohmann::json affinity = nlohmann::json::array();
    if (result.is_object() && result.contains("affinity") && result["affinity"].is_array() && result["affinity"].size() <= 4096)
        for (const auto& c : result["affinity"])
            if (c.is_number_unsigned()) affinity.push_back(c);

    RunRecordFields record;
    record.cell = cell;
    record.ok = o.ok;
    record.reason = o.reason;
    record.frames = frames.frames.size();
    record.frames_expected = unsigned_field(sequence, "frames_to_run");
    record.lost_frames = frames.lost_frames;
    record.dropped_frames = frames.dropped_frames;
    record.plugin = plugin;
    record.sequence = sequence;
    record.started = started;
    record.finished = utc_now_iso();
    record.child_outcome = ran ? child.describe() : "not started";
    record.processes_left_behind = child.left_behind;
    record.timing = timing;
    record.timing_protocol = timing_protocol(cell.timing, cell.limits.threads, affinity, pinned_core);
    record.metrics = metrics;
    record.evaluation = evaluation_error.empty() ? evaluation : nlohmann::json{{"error", evaluation_error}};
    if (fs::exists(work / "child.log")) keep_log_tail(work / "child.log", 64 * 1024);
    write_run_record(work, record);  // last: its presence marks the cell finished
    fs::remove_all(final_dir);
    fs::rename(work, final_dir);
    o.wall_s = child.wall_s;
    return o;
}

}  // namespace

bool cell_finished(const fs::path& out, const std::string& id) { return record_problem(ResultsDir(out).run_dir(id), id).empty(); }

CellOutcome run_cell(const Cell& cell, const fs::path& out, const std::atomic<bool>* cancel, int pinned_core) {
    return finish_cell(cell, out, "", cancel, pinned_core);
}

CellOutcome record_unrun_cell(const Cell& cell, const fs::path& out, const std::string& reason) {
    return finish_cell(cell, out, reason, nullptr, -1);
}

}  // namespace vobench
