#include "sweep/cell_runner.hpp"

#include "metrics/statistics.hpp"
#include "metrics/trajectory_io.hpp"
#include "report/run_record.hpp"
#include "run/track.hpp"
#include "sweep/host_info.hpp"
#include "util/subprocess.hpp"

#include <fmt/format.h>
#include <opencv2/core/utility.hpp>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/prctl.h>
#include <unistd.h>

namespace vobench {
namespace fs = std::filesystem;

namespace {

nlohmann::json read_json_file(const fs::path& file) {
    std::ifstream in(file);
    if (!in) return nullptr;
    nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
    return j.is_discarded() ? nlohmann::json(nullptr) : j;
}

void write_json_file(const fs::path& file, const nlohmann::json& j) { metrics::write_file_atomic(file, j.dump(2) + "\n"); }

// One line of frames.jsonl: everything the supervisor needs to rebuild trajectory.txt and timing.csv.
std::string frame_line(const FrameRecord& f, const metrics::StampedPose& p) {
    nlohmann::json j{{"i", f.index},
                     {"t", f.stamp},
                     {"ns", f.process_ns},
                     {"r", f.read_ns},
                     {"s", f.tracking},
                     {"p", {p.p.x(), p.p.y(), p.p.z(), p.q.x(), p.q.y(), p.q.z(), p.q.w()}}};
    for (const auto& [name, ns] : f.stages) j["st"][name] = ns;
    for (const auto& [name, v] : f.counters) j["c"][name] = v;
    return j.dump() + "\n";
}

// The stream back; a last line cut short by a crash is dropped.
TrackResult read_frames(const fs::path& file) {
    TrackResult r;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
        if (j.is_discarded() || !j.contains("p")) break;
        FrameRecord f;
        f.index = j["i"];
        f.stamp = j["t"];
        f.process_ns = j["ns"];
        f.read_ns = j.value("r", int64_t{0});
        f.tracking = j["s"];
        if (j.contains("st"))
            for (const auto& [name, ns] : j["st"].items()) f.stages.emplace_back(name, ns.get<int64_t>());
        if (j.contains("c"))
            for (const auto& [name, v] : j["c"].items()) f.counters.emplace_back(name, v.get<double>());
        const auto& p = j["p"];
        metrics::StampedPose sp;
        sp.t = f.stamp;
        sp.p = Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
        sp.q = Eigen::Quaterniond(p[6].get<double>(), p[3].get<double>(), p[4].get<double>(), p[5].get<double>());
        if (f.tracking != VOBENCH_TRACKING_OK) ++r.failed_frames;
        r.estimate.push_back(sp);
        r.frames.push_back(std::move(f));
    }
    return r;
}

// Per-frame times of the plugin's process() call only (steady clock, ns → ms), and the stages.
nlohmann::json timing_summary(const TrackResult& r, const nlohmann::json& result, const ChildResult& child) {
    std::vector<double> ms;
    double timed_ns = 0, read_ns = 0;
    std::vector<std::string> order;
    std::map<std::string, double> stage_ns;
    for (const FrameRecord& f : r.frames) {
        ms.push_back(static_cast<double>(f.process_ns) * 1e-6);
        timed_ns += static_cast<double>(f.process_ns);
        read_ns += static_cast<double>(f.read_ns);
        for (const auto& [name, ns] : f.stages) {
            if (!stage_ns.count(name)) order.push_back(name);
            stage_ns[name] += static_cast<double>(ns);
        }
    }
    const double n = static_cast<double>(std::max<std::size_t>(1, ms.size()));
    nlohmann::json stages = nlohmann::json::array();
    for (const std::string& s : order) stages.push_back({{"stage", s}, {"mean_ms", stage_ns[s] * 1e-6 / n}});
    const metrics::ErrorStats stats = ms.empty() ? metrics::ErrorStats{} : metrics::compute_stats(ms);  // numpy semantics
    const double loop_wall_s = result.is_object() ? result.value("loop_wall_ns", 0.0) * 1e-9 : 0.0;
    nlohmann::json j{{"frames", ms.size()},
                     {"mean_ms", stats.mean},
                     {"median_ms", stats.median},
                     {"p95_ms", ms.empty() ? 0.0 : metrics::percentile_nearest_rank(ms, 0.95)},
                     {"max_ms", stats.max},
                     {"fps", stats.mean > 0 ? 1000.0 / stats.mean : 0.0},
                     {"stages", stages},
                     {"timed_s", timed_ns * 1e-9},
                     {"read_s", read_ns * 1e-9},
                     {"read_ms_per_frame", read_ns * 1e-6 / n},
                     {"child_wall_s", child.wall_s},
                     {"peak_rss_mb", static_cast<double>(std::max<uint64_t>(child.peak_rss_kb, result.is_object() ? result.value("peak_rss_kb", uint64_t{0}) : 0)) / 1024.0}};
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
    metrics::write_file_atomic(log, fmt::format("[… {} bytes cut …]\n", size - max_bytes) + tail);
}

}  // namespace

bool cell_finished(const fs::path& out, const std::string& id) { return fs::exists(out / "runs" / id / "run.json"); }

int exec_cell(const fs::path& work) {
    // Die with the supervisor: a SIGKILLed vobench must not leave cells running into a resumed sweep.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() == 1) return 2;
    // A plugin that calls exit() does so while the frame-reading thread still runs; the static
    // destructors that exit() would run next can crash under it and turn "exited with code 3" into
    // a SIGSEGV. Registered last, this handler runs first and ends the process with the plugin's code.
    ::on_exit([](int status, void*) {
        std::fflush(nullptr);
        ::_exit(status);
    }, nullptr);
    const Cell cell = cell_from_json(read_json_file(work / "cell.json"));
    cv::setNumThreads(cell.limits.threads);
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(cell.limits.threads));

    std::FILE* stream = std::fopen((work / "frames.jsonl").c_str(), "w");
    if (!stream) {
        std::fprintf(stderr, "cannot write %s\n", (work / "frames.jsonl").c_str());
        return 2;
    }
    TrackOptions t;
    t.dataset = cell.reader;
    t.path = cell.path;
    t.dataset_options = cell.reader_options;
    t.algorithm = cell.plugin_file.empty() ? cell.plugin : cell.plugin_file;
    t.params = cell.params;
    t.seed = cell.seed;
    t.max_frames = cell.max_frames;
    t.evaluate = false;
    // One thread means one core: frames are decoded between process() calls (still outside the
    // timed window) instead of on a prefetch thread, so N cells on N cores do not compete.
    t.prefetch_depth = cell.limits.threads > 1 ? 4 : 0;
    t.on_start = [&](const vobench_sequence_info& info, const PluginLibrary& plugin) {
        metrics::write_tum(work / "groundtruth.txt", ground_truth_of(info), "ground truth as the reader delivered it");
        const vobench_camera& c = *info.camera;
        const uint64_t expected = cell.max_frames > 0 ? std::min(cell.max_frames, info.frame_count) : info.frame_count;
        write_json_file(work / "sequence.json",
                        {{"name", info.name ? info.name : ""},
                         {"sensor", info.sensor ? info.sensor : ""},
                         {"frame_count", info.frame_count},
                         {"frames_to_run", expected},
                         // The reader's declared ground-truth accuracy (API 2; -1: not known or an API-1 reader).
                         {"gt_position_sigma_m", VOBENCH_HAS_FIELD(&info, vobench_sequence_info, gt_position_sigma_m) ? info.gt_position_sigma_m : -1.0},
                         {"gt_rotation_sigma_deg", VOBENCH_HAS_FIELD(&info, vobench_sequence_info, gt_rotation_sigma_deg) ? info.gt_rotation_sigma_deg : -1.0},
                         {"camera", {{"width", c.width}, {"height", c.height}, {"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}}}});
        const vobench_plugin_descriptor& d = plugin.descriptor();
        write_json_file(work / "plugin.json", {{"name", plugin.name()},
                                               {"version", d.version ? d.version : ""},
                                               {"licence", d.license ? d.license : ""},
                                               {"abi_version", d.abi_version},
                                               {"api_version", d.api_version},
                                               {"file", plugin.path().string()}});
    };
    t.on_frame = [&](const FrameRecord& f, const metrics::StampedPose& p) {
        const std::string line = frame_line(f, p);
        std::fwrite(line.data(), 1, line.size(), stream);
        std::fflush(stream);  // into the kernel: survives the process dying on the next frame
    };
    nlohmann::json result;
    try {
        const TrackResult r = run_track(t, PluginRegistry());
        int64_t timed = 0;
        for (const FrameRecord& f : r.frames) timed += f.process_ns;
        result = {{"status", r.error.empty() ? "ok" : "failed"}, {"error", r.error}, {"frames", r.frames.size()},
                  {"loop_wall_ns", r.loop_wall_ns}, {"timed_ns", timed}};
    } catch (const std::exception& e) {  // the reader or plugin could not start: a failed row, not a crash
        result = {{"status", "failed"}, {"error", std::string("setting up: ") + e.what()}, {"frames", 0}};
    }
    std::fclose(stream);
    result["peak_rss_kb"] = peak_resident_kb("self");  // exact at the end; the supervisor's samples cover a crash
    write_json_file(work / "result.json", result);
    return 0;
}

namespace {

// Runs the cell's child unless `not_run_reason` is given, then turns whatever it left into runs/<id>/.
CellOutcome finish_cell(const Cell& cell, const fs::path& out, std::string not_run_reason, const std::atomic<bool>* cancel) {
    const fs::path work = out / "runs" / ".work" / cell.id;
    const fs::path final_dir = out / "runs" / cell.id;
    fs::remove_all(work);
    fs::create_directories(work);
    write_json_file(work / "cell.json", cell_to_json(cell));
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
        child = run_self_limited({"cell-exec", work.string()}, limits);
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
    TrackResult frames = read_frames(work / "frames.jsonl");
    const nlohmann::json result = read_json_file(work / "result.json");
    // Absent when the child died before the sequence opened: empty objects, never null.
    nlohmann::json sequence = read_json_file(work / "sequence.json"), plugin = read_json_file(work / "plugin.json");
    if (!sequence.is_object()) sequence = nlohmann::json::object();
    if (!plugin.is_object()) plugin = nlohmann::json::object();

    CellOutcome o;
    o.id = cell.id;
    o.frames = frames.frames.size();
    if (!ran) {
        o.reason = not_run_reason;
    } else if (result.is_object() && child.exited && child.exit_code == 0) {
        o.ok = result.value("status", "") == "ok";
        o.reason = result.value("error", "");
    } else if (result.is_object()) {
        o.reason = fmt::format("{} after the last frame (while shutting down)", child.describe());
    } else {
        o.reason = fmt::format("{} at frame {}", child.describe(), frames.frames.size());
    }
    if (!o.ok && o.reason.empty()) o.reason = "failed without a message";

    write_track_outputs(frames, work);
    std::string evaluation_error;
    nlohmann::json evaluation;
    MetricMap metrics = evaluate_run_files(work, cell.protocol, evaluation_error, &evaluation);
    const uint64_t to_run = sequence.value("frames_to_run", uint64_t{0});
    const nlohmann::json timing = timing_summary(frames, result, child);

    nlohmann::json run{{"schema_version", 1},
                       {"cell", cell_to_json(cell)},
                       {"status", o.ok ? "ok" : "failed"},
                       {"reason", o.reason},
                       {"failed_at_frame", o.ok ? nlohmann::json(nullptr) : nlohmann::json(frames.frames.size())},
                       {"partial", !o.ok && !frames.frames.empty()},
                       {"frames", frames.frames.size()},
                       {"frames_expected", to_run},
                       {"lost_frames", frames.failed_frames},
                       {"plugin", plugin},
                       {"sequence", sequence},
                       {"host", host_info()},
                       {"started", started},
                       {"finished", utc_now_iso()},
                       {"child", {{"outcome", ran ? child.describe() : "not started"}, {"log", "child.log"}}},
                       {"timing", timing},
                       {"metrics", metrics},
                       {"evaluation", evaluation_error.empty() ? evaluation : nlohmann::json{{"error", evaluation_error}}}};
    if (fs::exists(work / "child.log")) keep_log_tail(work / "child.log", 64 * 1024);
    write_json_file(work / "run.json", run);  // last: its presence marks the cell finished
    fs::remove_all(final_dir);
    fs::rename(work, final_dir);
    o.wall_s = child.wall_s;
    return o;
}

}  // namespace

CellOutcome run_cell(const Cell& cell, const fs::path& out, const std::atomic<bool>* cancel) { return finish_cell(cell, out, "", cancel); }

CellOutcome record_unrun_cell(const Cell& cell, const fs::path& out, const std::string& reason) {
    return finish_cell(cell, out, reason, nullptr);
}

}  // namespace vobench
