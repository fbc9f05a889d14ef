// Approval tests (Catch2 v3's approach): the report's outputs for a fixed set of run records —
// summary.md, summary.csv, summary.tex, leaderboard.json and report.html — against the approved copies
// in tests/approved/. What differs between machines and builds (the host, the vobench version) is
// normalised first. A mismatch writes <name>.received.<ext> beside the approved file, to diff;
// VOBENCH_APPROVE=1 makes the received outputs the approved ones.
#include "metrics/metric_catalog.hpp"
#include "record/run_record.hpp"
#include "report/aggregate.hpp"
#include "report/html_report.hpp"
#include "report/leaderboard.hpp"
#include "report/report_assets.hpp"
#include "report/tables.hpp"
#include "util/files.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

RunRecord record(const std::string& algorithm, const ParamMap& params, const std::string& sequence, const std::string& sensor,
                 uint64_t repeat, double ate, bool ok = true) {
    RunRecord r;
    r.cell.algorithm = r.cell.plugin = algorithm;
    r.cell.params = params;
    r.cell.dataset = "sim";
    r.cell.sequence = sequence;
    r.cell.sensor = sensor;
    r.cell.repeat = repeat;
    r.cell.seed = repeat + 1;
    r.cell.id = "00000000000000" + std::to_string(10 + repeat);
    r.cell.gt_accuracy = {sequence == "s2" ? 0.002 : 0.0, 0.0};
    r.ok = ok;
    r.reason = ok ? "" : "killed by signal 11 (SIGSEGV) at frame 7";
    r.partial = !ok;
    const double ms = 1.25 + 0.5 * static_cast<double>(repeat) + (sensor == "kinect2" ? 2.0 : 0.0);
    r.run = {{"plugin", {{"version", "1.0"}}},
             {"frames", ok ? 50 : 7},
             {"failed_at_frame", ok ? nlohmann::json(nullptr) : nlohmann::json(7)},
             {"timing",
              {{"frames", 50},
               {"mean_ms", ms},
               {"median_ms", ms},
               {"p95_ms", ms * 1.5},
               {"max_ms", ms * 2},
               {"fps", 1000 / ms},
               {"read_ms_per_frame", 8.5},
               {"peak_rss_mb", 70.0},
               {"harness_overhead_pct", 0.25},
               {"stages", {{{"stage", "detection"}, {"mean_ms", ms / 2}}, {{"stage", "tracking"}, {"mean_ms", ms / 4}}}}}}};
    if (ok) {
        r.metrics["ate.rmse"] = ate;
        r.metrics["ate.std"] = ate / 3;
        r.metrics["rpe.trans.rmse"] = ate / 2;
        r.metrics["rpe.rot.rmse"] = ate * 10;
        r.metrics["ms_per_frame"] = ms;
        r.metrics["fps"] = 1000 / ms;
    }
    r.metrics["lost_frames"] = repeat;
    r.metrics["failed_frames"] = repeat + (ok ? 0 : 43);
    return r;
}

std::vector<RunRecord> fixture() {
    std::vector<RunRecord> rs;
    for (const char* seq : {"s1", "s2"})
        for (const char* sensor : {"kinect1", "kinect2"})
            for (uint64_t k = 0; k < 2; ++k) {
                const double v2 = std::string(sensor) == "kinect2" ? 0.5 : 1.0;
                rs.push_back(record("alpha", {{"k", "1"}}, seq, sensor, k, v2 * (0.010 + 0.001 * static_cast<double>(k))));
                rs.push_back(record("beta", {}, seq, sensor, k, v2 * (0.020 + 0.002 * static_cast<double>(k)),
                                    !(k == 1 && std::string(seq) == "s2")));
                rs.push_back(record("odd | <b>name</b> \\_x_", {}, seq, sensor, k, v2 * 0.015));
            }
    return rs;
}

// The host and the vobench build are facts of the machine, not of the report's logic.
nlohmann::json normalised(nlohmann::json lb) {
    lb["context"]["vobench_version"] = "<version>";
    lb["context"]["host"] = {{"cpu", "<cpu>"}};
    return lb;
}

// The embedded libraries are the build's (report/report_assets.hpp, tested on their own): their text
// is replaced by a line naming them, so that the approved page shows what the report itself wrote.
std::string without_embedded_scripts(std::string html) {
    for (const auto& [text, name] : {std::pair{plotly_js(), "plotly.js"}, std::pair{report_app_js(), "report_app.js"}}) {
        const std::size_t at = html.find(text);
        REQUIRE(at != std::string::npos);
        html.replace(at, text.size(), std::string("/* <") + name + " embedded here> */");
    }
    return html;
}

void approve(const std::string& name, const std::string& received) {
    const fs::path approved = fs::path(VOBENCH_SOURCE_DIR) / "tests" / "approved" / name;
    fs::path received_file = approved;
    received_file.replace_extension(".received" + approved.extension().string());
    if (const char* a = std::getenv("VOBENCH_APPROVE"); a && std::string(a) == "1") {
        write_file_atomic(approved, received);
        WARN("approved " << approved.string());
        return;
    }
    std::string expected;
    try {
        expected = read_file(approved);
    } catch (const std::exception&) {
        FAIL(approved.string() << " is missing: run the test with VOBENCH_APPROVE=1 and review the file");
    }
    if (expected != received) write_file_atomic(received_file, received);
    INFO("differs from the approved copy: diff " << approved.string() << " " << received_file.string());
    CHECK(expected == received);
}

}  // namespace

TEST_CASE("report outputs equal their approved copies", "[report][approval]") {
    const std::vector<RunRecord> records = fixture();
    const std::vector<RunGroup> groups = group_runs(records);
    ReportContext ctx;
    ctx.name = "approval fixture";
    ctx.generated = "2026-01-01T00:00:00.000Z";
    ctx.protocol_text = "Protocol 'paper': association within 0.02 s. ATE after se3 alignment. RPE at Δ = 4 f.";
    ctx.problems = {"0000000000000099: missing (in cells.json, no record under runs/)"};
    LeaderboardContext lctx;
    lctx.name = ctx.name;
    lctx.generated = ctx.generated;
    lctx.rank_by = "ate.rmse";
    lctx.protocol = metrics::protocol_json(metrics::Protocol{});
    lctx.criteria = {parse_criterion("rpe.trans.rmse <= 0.008"), parse_criterion("failed_cells == 0")};
    const nlohmann::json lb = normalised(build_leaderboard(records, lctx));

    approve("summary.approved.md", summary_markdown(groups, ctx));
    approve("summary.approved.csv", summary_csv(groups));
    approve("summary.approved.tex", summary_latex(groups, ctx));
    approve("leaderboard.approved.json", json_text(lb) + "\n");
    approve("report.approved.html", without_embedded_scripts(render_html_report(groups, lb, {}, fs::temp_directory_path(), ctx)));
}
