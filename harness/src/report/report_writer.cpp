#include "report/report_writer.hpp"

#include "metrics/metric_catalog.hpp"
#include "metrics/trajectory_io.hpp"
#include "record/host_info.hpp"
#include "record/run_record.hpp"
#include "report/aggregate.hpp"
#include "report/figures.hpp"
#include "report/html_report.hpp"
#include "report/leaderboard.hpp"
#include "report/tables.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>

#include <set>

namespace vobench {
namespace fs = std::filesystem;

namespace {

// The cells' timing protocols (run.json timing_protocol) in one paragraph; values that differ between
// cells are all listed.
std::string timing_text(const std::vector<RunRecord>& records) {
    std::set<std::string> modes, warmups, threads, pinning, cpus, governors;
    for (const RunRecord& r : records) {
        const nlohmann::json p = r.run.value("timing_protocol", nlohmann::json::object());
        if (!p.is_object() || !p.contains("mode") || !p["mode"].is_string()) continue;
        const std::string mode = p["mode"];
        modes.insert(mode == "realtime"
                         ? fmt::format("real time at ×{:g} (a frame arriving while the plugin is busy is dropped)", p.value("speed", 1.0))
                         : "offline (every frame, as fast as the plugin goes)");
        warmups.insert(fmt::format("{}", p.value("warmup_frames", 0)));
        threads.insert(fmt::format("{}", p.value("threads_allowed", 1)));
        pinning.insert(p.value("pinned_core", -1) >= 0 ? "each pinned to a core of its own" : "not pinned");
        cpus.insert(clean_text(p.value("cpu_model", std::string("unknown"))));
        governors.insert(clean_text(p.value("governor", std::string("unknown"))));
    }
    if (modes.empty()) return "";
    const auto all = [](const std::set<std::string>& v) {
        std::string t;
        for (const std::string& s : v) t += (t.empty() ? "" : " / ") + s;
        return t;
    };
    return fmt::format(
        "Timing: {}; the first {} processed frame(s) of each cell left out of the statistics; {} thread(s) per cell, cells {}; CPU {}, "
        "frequency governor: {}. Timed: the plugin's process() call only (steady clock), reading frames outside the window; CPU/wall: "
        "the process's CPU time during the call over its wall time (above 1: the plugin ran threads of its own).",
        all(modes), all(warmups), all(threads), all(pinning), all(cpus), all(governors));
}

}  // namespace

// The evaluation protocol as used, with the reference that defines it: the paper's RPE (Kraft et al.
// 2016, eqs. 11–12) or the TUM benchmark's scripts (Sturm et al. 2012; evaluate_ate.py and
// evaluate_rpe.py, reproduced exactly), never one named for the other.
std::string protocol_text(const nlohmann::json& p) {
    if (!p.is_object() || !p.contains("name") || !p["name"].is_string()) return "";
    // Read from a results folder, which may be hand-edited: a field of the wrong type reads as its default.
    const auto text_of = [](const nlohmann::json& j, const char* key, const char* fallback) {
        return j.contains(key) && j[key].is_string() ? clean_text(j[key].get<std::string>()) : std::string(fallback);
    };
    const auto number_of = [](const nlohmann::json& j, const char* key, double fallback) {
        return j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
    };
    const bool tum = p["name"] == "tum-scripts";
    std::string text = fmt::format("Protocol '{}': colour stamps matched to ground truth within {} s", text_of(p, "name", ""),
                                   number_of(p, "max_difference_s", 0.02));
    if (number_of(p, "offset_s", 0) != 0) text += fmt::format(" after adding {} s to the estimate's stamps", number_of(p, "offset_s", 0));
    text += ".";
    if (p.contains("ate") && p["ate"].is_object()) {
        text += fmt::format(" ATE after {} alignment", text_of(p["ate"], "alignment", "se3"));
        if (number_of(p["ate"], "align_first", 0) > 0)
            text += fmt::format(" on the first {} matched poses", number_of(p["ate"], "align_first", 0));
        text += tum && text_of(p["ate"], "alignment", "se3") == "se3" ? " (Horn's closed form, as evaluate_ate.py)." : ".";
    }
    if (p.contains("rpe") && p["rpe"].is_object())
        text += fmt::format(" RPE at Δ = {} {}{}", number_of(p["rpe"], "delta", 4), text_of(p["rpe"], "delta_unit", "f"),
                            tum ? "." : " (Kraft et al. 2016, eqs. 11–12).");
    if (tum)
        text +=
            " Definitions: the TUM RGB-D benchmark's (Sturm et al. 2012), computed as its scripts evaluate_ate.py and evaluate_rpe.py "
            "compute them.";
    return text;
}

ReportResult write_report(const fs::path& out, bool re_evaluate) {
    nlohmann::json sweep = read_json_or_null(out / "sweep.json", 16 << 20);
    if (!sweep.is_object()) {
        if (fs::exists(out / "sweep.json")) spdlog::warn("{}: unreadable, using defaults", (out / "sweep.json").string());
        sweep = nlohmann::json::object();
    }
    std::vector<std::string> problems;
    LoadOptions load;
    load.re_evaluate = re_evaluate;
    const std::vector<RunRecord> records = load_runs(out, &problems, load);
    if (records.empty())
        throw std::runtime_error((out / "runs").string() + ": no finished cells to report" +
                                 (problems.empty() ? std::string() : " (" + std::to_string(problems.size()) + " missing or unsound)"));
    const std::vector<RunGroup> groups = group_runs(records);

    ReportContext ctx;
    ctx.generated = utc_now_iso();
    ctx.problems = problems;
    LeaderboardContext lctx;
    const nlohmann::json default_protocol = records.front().run["cell"]["protocol"];
    // sweep.json is a file like any other: a value of the wrong type, an unknown metric or a bad
    // criterion makes the report use the defaults and say so, never stop it.
    const auto read_settings = [&](const nlohmann::json& s) {
        ctx.name = clean_text(s.value("name", out.filename().string()));
        ctx.rank_by = s.value("rank_by", std::string("ate.rmse"));
        if (metrics::find_metric(ctx.rank_by) == nullptr) throw std::invalid_argument("unknown rank_by metric");
        lctx.protocol = s.contains("protocol") ? s["protocol"] : default_protocol;
        metrics::protocol_from_json(lctx.protocol);
        lctx.criteria.clear();
        for (const auto& c : s.value("criteria", nlohmann::json::array())) {
            Criterion k = parse_criterion(c.at("criterion"));
            k.required = c.value("required", true);
            lctx.criteria.push_back(k);
        }
    };
    try {
        read_settings(sweep);
    } catch (const std::exception& e) {
        spdlog::warn("{}: not usable ({}); the report uses the defaults", (out / "sweep.json").string(), clean_text(e.what()));
        read_settings(nlohmann::json::object());
    }
    ctx.protocol_text = protocol_text(lctx.protocol);
    ctx.timing_text = timing_text(records);
    lctx.name = ctx.name;
    lctx.rank_by = ctx.rank_by;
    lctx.generated = ctx.generated;
    const nlohmann::json leaderboard = build_leaderboard(records, lctx);

    write_file_atomic(out / "summary.md", summary_markdown(groups, ctx));
    write_file_atomic(out / "summary.csv", summary_csv(groups));
    write_file_atomic(out / "summary.tex", summary_latex(groups, ctx));
    write_json_atomic(out / "leaderboard.json", leaderboard);
    const std::vector<Figure> figures = write_figures(groups, out / "figures");
    write_file_atomic(out / "report.html", render_html_report(groups, leaderboard, figures, out / "figures", ctx));

    ReportResult r;
    r.runs = records.size();
    for (const RunRecord& rec : records) r.failed += rec.ok ? 0 : 1;
    r.accuracy_markdown = accuracy_markdown(groups);
    r.problems = problems;
    for (const auto& e : leaderboard["entries"])
        for (const auto& c : e["criteria"])
            if (c["required"].get<bool>() && !c["passed"].get<bool>())
                r.failed_required.push_back(e["entry"].get<std::string>() + ": " + c["criterion"].get<std::string>());
    return r;
}

}  // namespace vobench
