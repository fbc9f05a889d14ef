#include "report/report_writer.hpp"

#include "metrics/trajectory_io.hpp"
#include "report/aggregate.hpp"
#include "report/figures.hpp"
#include "report/html_report.hpp"
#include "report/leaderboard.hpp"
#include "report/run_record.hpp"
#include "report/tables.hpp"
#include "sweep/host_info.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <fstream>

namespace vobench {
namespace fs = std::filesystem;

nlohmann::json sweep_record(const SweepConfig& c) {
    nlohmann::json criteria = nlohmann::json::array();
    for (const Criterion& k : c.criteria) criteria.push_back({{"criterion", k.text}, {"required", k.required}});
    return {{"name", c.name}, {"config_file", c.file.string()}, {"rank_by", c.rank_by}, {"criteria", criteria},
            {"protocol", metrics::protocol_json(c.protocol)}, {"config", c.source}};
}

namespace {

std::string protocol_text(const nlohmann::json& p) {
    if (!p.is_object() || !p.contains("name")) return "";
    std::string text = fmt::format("Protocol '{}': association within {} s.", p["name"].get<std::string>(), p.value("max_difference_s", 0.02));
    if (p.contains("ate")) text += fmt::format(" ATE after {} alignment.", p["ate"].value("alignment", "se3"));
    if (p.contains("rpe")) text += fmt::format(" RPE at Δ = {} {} (Kraft et al. 2016, eqs. 11–12).", p["rpe"].value("delta", 4.0), p["rpe"].value("delta_unit", "f"));
    return text;
}

}  // namespace

ReportResult write_report(const fs::path& out) {
    nlohmann::json sweep = nlohmann::json::object();
    if (std::ifstream in(out / "sweep.json"); in) {
        sweep = nlohmann::json::parse(in, nullptr, false);
        if (sweep.is_discarded()) {
            spdlog::warn("{}: unreadable, using defaults", (out / "sweep.json").string());
            sweep = nlohmann::json::object();
        }
    }
    const std::vector<RunRecord> records = load_runs(out);
    if (records.empty()) throw std::runtime_error((out / "runs").string() + ": no finished cells to report");
    const std::vector<RunGroup> groups = group_runs(records);

    ReportContext ctx;
    ctx.name = sweep.value("name", out.filename().string());
    ctx.rank_by = sweep.value("rank_by", std::string("ate.rmse"));
    ctx.generated = utc_now_iso();
    const nlohmann::json protocol = sweep.contains("protocol") ? sweep["protocol"] : records.front().run["cell"]["protocol"];
    ctx.protocol_text = protocol_text(protocol);

    LeaderboardContext lctx;
    lctx.name = ctx.name;
    lctx.rank_by = ctx.rank_by;
    lctx.protocol = protocol;
    lctx.generated = ctx.generated;
    for (const auto& c : sweep.value("criteria", nlohmann::json::array())) {
        Criterion k = parse_criterion(c.at("criterion"));
        k.required = c.value("required", true);
        lctx.criteria.push_back(k);
    }
    const nlohmann::json leaderboard = build_leaderboard(records, lctx);

    metrics::write_file_atomic(out / "summary.md", summary_markdown(groups, ctx));
    metrics::write_file_atomic(out / "summary.csv", summary_csv(groups));
    metrics::write_file_atomic(out / "summary.tex", summary_latex(groups, ctx));
    metrics::write_file_atomic(out / "leaderboard.json", leaderboard.dump(2) + "\n");
    const std::vector<Figure> figures = write_figures(groups, out / "figures");
    metrics::write_file_atomic(out / "report.html", render_html_report(groups, leaderboard, figures, out / "figures", ctx));

    ReportResult r;
    r.runs = records.size();
    for (const RunRecord& rec : records) r.failed += rec.ok ? 0 : 1;
    r.accuracy_markdown = accuracy_markdown(groups);
    for (const auto& e : leaderboard["entries"])
        for (const auto& c : e["criteria"])
            if (c["required"].get<bool>() && !c["passed"].get<bool>())
                r.failed_required.push_back(e["entry"].get<std::string>() + ": " + c["criterion"].get<std::string>());
    return r;
}

}  // namespace vobench
