#include "report/html_report.hpp"

#include "report/interactive_page.hpp"
#include "report/trajectory_view.hpp"

#include "util/escape.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace vobench {
namespace fs = std::filesystem;

namespace {

std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8) | uint8_t(bytes[i + 2]);
        out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
    }
    if (i + 1 == bytes.size()) {
        const uint32_t v = uint8_t(bytes[i]) << 16;
        out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == bytes.size()) {
        const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8);
        out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
    }
    return out;
}

std::string read_binary(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string num(const nlohmann::json& agg, const std::string& metric, int decimals) {
    if (!agg.contains(metric) || !agg[metric].contains("mean")) return "";
    return fmt::format("{:.{}f}", agg[metric]["mean"].get<double>(), decimals);
}

const char* kStyle = R"(
body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1200px;color:#222;padding:0 1em}
table{border-collapse:collapse;margin:1em 0;font-size:0.9em}th,td{border:1px solid #ccc;padding:3px 8px;text-align:right}
th{background:#f2f2f2;cursor:default}td.l,th.l{text-align:left}table.sortable th{cursor:pointer}
tr.failed td{background:#fdecea}.tie{color:#8a6d00}.pass{color:#1b7f1b}.fail{color:#b00020}
figure{display:inline-block;margin:0.5em;vertical-align:top}figure img{max-width:560px;border:1px solid #ddd}
figcaption{font-size:0.85em;max-width:560px}pre{background:#f7f7f7;padding:1em;overflow:auto}
)";

// Sorts a table by the clicked column (numbers as numbers, empty last); records the row count so a
// test can see the script ran.
const char* kScript = R"(
document.querySelectorAll('table.sortable').forEach(function(table){
  var body=table.tBodies[0];
  table.dataset.rows=body.rows.length;
  table.querySelectorAll('th').forEach(function(th,col){
    th.addEventListener('click',function(){
      var asc=th.dataset.dir!=='asc';th.dataset.dir=asc?'asc':'desc';
      var rows=Array.prototype.slice.call(body.rows);
      rows.sort(function(a,b){
        var x=a.cells[col].dataset.v!==undefined?a.cells[col].dataset.v:a.cells[col].textContent;
        var y=b.cells[col].dataset.v!==undefined?b.cells[col].dataset.v:b.cells[col].textContent;
        var nx=parseFloat(x),ny=parseFloat(y);
        if(x===''&&y!=='')return 1;if(y===''&&x!=='')return -1;
        var c=(!isNaN(nx)&&!isNaN(ny))?nx-ny:String(x).localeCompare(String(y));
        return asc?c:-c;});
      rows.forEach(function(r){body.appendChild(r);});
    });
  });
});
document.body.dataset.ready='yes';
)";

std::string leaderboard_table(const nlohmann::json& lb) {
    const std::string primary = lb["context"]["primary_metric"];
    std::string h = "<table class=\"sortable filterable\" id=\"leaderboard\"><thead><tr><th>rank</th><th class=\"l\">entry</th><th>" +
                    html_text(primary) +
                    " (mean)</th><th>95 % interval</th><th>ATE RMSE [m]</th><th>RPE RMSE [m]</th><th>RPE RMSE [°]</th><th>fps</th>"
                    "<th>cells</th><th>failed</th><th class=\"l\">tied with</th><th class=\"l\">criteria</th></tr></thead><tbody>\n";
    for (const auto& e : lb["entries"]) {
        const auto& agg = e["aggregate"];
        std::string ci;
        if (agg.contains(primary) && agg[primary].contains("ci95"))
            ci = fmt::format("[{:.4f}, {:.4f}]", agg[primary]["ci95"][0].get<double>(), agg[primary]["ci95"][1].get<double>());
        // At most five names in the cell (a wide sweep ties dozens); all of them in leaderboard.json.
        std::string ties;
        std::size_t shown = 0;
        for (const auto& t : e["tied_with"])
            if (shown++ < 5) ties += (ties.empty() ? "" : ", ") + html_text(t.get<std::string>());
        if (shown > 5) ties += fmt::format(" and {} more", shown - 5);
        std::string crit;
        for (const auto& c : e["criteria"])
            crit += fmt::format("<span class=\"{}\">{} {}</span><br>", c["passed"].get<bool>() ? "pass" : "fail",
                                c["passed"].get<bool>() ? "✔" : "✘", html_text(c["criterion"].get<std::string>()));
        const std::string rank = e["rank"].is_null() ? "" : std::to_string(e["rank"].get<int>());
        h += fmt::format(
            "<tr class=\"{}\" data-entry=\"{}\"><td data-v=\"{}\">{}</td><td "
            "class=\"l\">{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>"
            "<td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"l tie\">{}</td><td class=\"l\">{}</td></tr>\n",
            e["complete"].get<bool>() ? "entry" : "entry failed", html_text(e["entry"].get<std::string>()), rank, rank.empty() ? "–" : rank,
            html_text(e["entry"].get<std::string>()), num(agg, primary, 4), ci, num(agg, "ate.rmse", 4), num(agg, "rpe.trans.rmse", 4),
            num(agg, "rpe.rot.rmse", 3), num(agg, "fps", 1), e["cells"].size(), e["failed_cells"].get<int>(), ties, crit);
    }
    return h + "</tbody></table>\n";
}

std::string accuracy_tables(const std::vector<RunGroup>& groups) {
    static const std::pair<const char*, int> cols[] = {{"ate.rmse", 4}, {"ate.std", 4}, {"rpe.trans.rmse", 4}, {"rpe.rot.rmse", 3}};
    std::string h;
    for (const std::string& entry : entries_of(groups)) {
        const auto sensors = sensors_of(groups, entry);
        // A data set without sensor names (one camera) gets no sensor row.
        const bool sensor_row = !(sensors.size() == 1 && sensors.front().empty());
        h += "<h3>" + html_text(entry) + "</h3>\n<table class=\"table5\"><thead><tr><th class=\"l\"" +
             (sensor_row ? " rowspan=\"2\"" : "") + ">sequence</th>";
        if (sensor_row) {
            for (const std::string& s : sensors) h += "<th colspan=\"4\">" + html_text(sensor_title(s)) + "</th>";
            h += "</tr><tr>";
        }
        for (std::size_t k = 0; k < sensors.size(); ++k)
            h += "<th>ATE RMSE [m]</th><th>ATE std [m]</th><th>RPE RMSE [m]</th><th>RPE RMSE [°]</th>";
        h += "</tr></thead><tbody>\n";
        for (const std::string& row : rows_of(groups, entry)) {
            h += "<tr><td class=\"l\">" + html_text(row) + "</td>";
            for (const std::string& s : sensors) {
                const RunGroup* g = find_group(groups, entry, row, s);
                const double pos = g ? g->runs.front()->cell.gt_accuracy.position_m : 0,
                             rot = g ? g->runs.front()->cell.gt_accuracy.rotation_deg : 0;
                for (const auto& [metric, dec] : cols)
                    h += "<td>" + html_text(format_metric(g, metric, dec, std::string(metric).rfind("rpe.rot", 0) == 0 ? rot : pos)) +
                         "</td>";
            }
            h += "</tr>\n";
        }
        h += "</tbody></table>\n";
    }
    return h;
}

// The attributes the page's filters read (report_app.js setUpFilters).
std::string filter_attributes(const RunGroup& g) {
    return "data-entry=\"" + html_text(g.entry) + "\" data-row=\"" + html_text(g.row_label()) + "\" data-sensor=\"" +
           html_text(sensor_title(g.sensor)) + "\"";
}

// One row per entry × sequence × sensor, means over its repeats; a row with a trajectory to show opens
// it in the explorer (data-view: its index in the data island's views).
std::string cells_table(const std::vector<RunGroup>& groups, const std::vector<long>& view_of) {
    std::string h =
        "<table class=\"sortable filterable\" id=\"cells\"><thead><tr><th class=\"l\">entry</th><th class=\"l\">sequence</th>"
        "<th class=\"l\">sensor</th><th>repeats</th><th>failed</th><th>ATE RMSE [m]</th><th>RPE RMSE [m]</th><th>RPE RMSE [°]</th>"
        "<th>ms/frame</th><th class=\"l\">view</th></tr></thead><tbody>\n";
    const auto mean = [](const RunGroup& g, const char* metric, int d) {
        const auto m = summarize(g, metric);
        return m ? fmt::format("{:.{}f}", m->mean, d) : std::string();
    };
    for (std::size_t k = 0; k < groups.size(); ++k) {
        const RunGroup& g = groups[k];
        const std::string view = view_of[k] >= 0 ? fmt::format(" data-view=\"{}\"", view_of[k]) : "";
        h += fmt::format(
            "<tr {}{}><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>"
            "<td>{}</td><td>{}</td><td class=\"l\">{}</td></tr>\n",
            filter_attributes(g), view, html_text(g.entry), html_text(g.row_label()), html_text(sensor_title(g.sensor)), g.runs.size(),
            g.failed(), mean(g, "ate.rmse", 4), mean(g, "rpe.trans.rmse", 4), mean(g, "rpe.rot.rmse", 3), mean(g, "ms_per_frame", 3),
            view_of[k] >= 0 ? "▶ show" : "no trajectory");
    }
    return h + "</tbody></table>\n";
}

std::string timing_table(const std::vector<RunGroup>& groups) {
    std::string h =
        "<table class=\"sortable filterable\" id=\"timing\"><thead><tr><th class=\"l\">entry</th><th class=\"l\">sequence</th><th "
        "class=\"l\">sensor</th>"
        "<th>mean [ms]</th><th>median</th><th>p95</th><th>max</th><th>fps</th><th>reading [ms]</th><th>peak RSS [MB]</th><th>overhead "
        "[%]</th><th>CPU/wall</th><th>dropped</th>"
        "<th class=\"l\">stages [ms/frame]</th></tr></thead><tbody>\n";
    const auto v = [](const std::optional<double>& x, int d) { return x ? fmt::format("{:.{}f}", *x, d) : std::string(); };
    for (const RunGroup& g : groups) {
        std::string stages;
        for (const std::string& s : stages_of(groups, g.entry))
            if (const auto ms = stage_mean_ms(g, s)) stages += fmt::format("{} {:.3f}; ", html_text(s), *ms);
        h += fmt::format(
            "<tr {}><td class=\"l\">{}</td><td class=\"l\">{}</td><td "
            "class=\"l\">{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>"
            "<td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"l\">{}</td></tr>\n",
            filter_attributes(g), html_text(g.entry), html_text(g.row_label()), html_text(sensor_title(g.sensor)),
            v(timing_mean(g, "mean_ms"), 3), v(timing_mean(g, "median_ms"), 3), v(timing_mean(g, "p95_ms"), 3),
            v(timing_mean(g, "max_ms"), 3), v(timing_mean(g, "fps"), 1), v(timing_mean(g, "read_ms_per_frame"), 3),
            v(timing_mean(g, "peak_rss_mb"), 0), v(timing_mean(g, "harness_overhead_pct"), 1), v(timing_mean(g, "cpu_per_wall"), 2),
            v(timing_mean(g, "dropped_frames"), 1), stages);
    }
    return h + "</tbody></table>\n";
}

std::string failures_table(const nlohmann::json& lb) {
    if (lb["failures"].empty()) return "<p>No cell failed.</p>\n";
    std::string h =
        "<table id=\"failures\"><thead><tr><th class=\"l\">cell</th><th class=\"l\">entry</th><th class=\"l\">sequence</th>"
        "<th class=\"l\">sensor</th><th class=\"l\">reason</th><th>frames kept</th></tr></thead><tbody>\n";
    for (const auto& f : lb["failures"])
        h += fmt::format(
            "<tr class=\"failed\"><td class=\"l\">{}</td><td class=\"l\">{}</td><td class=\"l\">{}/{}</td><td class=\"l\">{}</td>"
            "<td class=\"l\">{}</td><td>{}</td></tr>\n",
            html_text(f["id"].get<std::string>().substr(0, 12)), html_text(f["entry"].get<std::string>()),
            html_text(f["dataset"].get<std::string>()), html_text(f["sequence"].get<std::string>()),
            html_text(sensor_title(f["sensor"].get<std::string>())), html_text(f["reason"].get<std::string>()),
            f["failed_at_frame"].is_null() ? std::string("0") : std::to_string(f["failed_at_frame"].get<long long>()));
    return h + "</tbody></table>\n";
}

}  // namespace

std::string render_html_report(const std::vector<RunGroup>& groups, const nlohmann::json& lb, const std::vector<Figure>& figures,
                               const fs::path& figure_folder, const ReportContext& ctx) {
    // The explorer's views: the first successful, evaluated repeat of each entry × sequence × sensor
    // (the cells the figures draw).
    nlohmann::json views = nlohmann::json::array();
    std::vector<long> view_of(groups.size(), -1);
    for (std::size_t k = 0; k < groups.size(); ++k)
        for (const RunRecord* r : groups[k].runs)
            if (r->evaluation) {
                if (auto v = cell_view(*r)) {
                    view_of[k] = static_cast<long>(views.size());
                    views.push_back(std::move(*v));
                }
                break;
            }
    std::string h = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n" + page_head_security() + "<title>" +
                    html_text(ctx.name) + " — vobench report</title>\n<style>" + kStyle + explorer_style() + "</style></head>\n<body>\n";
    h += "<h1>" + html_text(ctx.name) + " — vobench report</h1>\n";
    h += "<p>Generated " + html_text(ctx.generated) + " by vobench " + html_text(lb["context"]["vobench_version"].get<std::string>()) +
         " on " + html_text(lb["context"]["host"]["cpu"].get<std::string>()) + ". " + html_text(ctx.protocol_text) + "</p>\n";
    h += "<h2>Leaderboard</h2>\n<p>Ranked by " + html_text(ctx.rank_by) +
         " over each entry's cells; entries with a failed cell are not ranked. Ties: 95 % bootstrap intervals overlap. "
         "Click a column to sort.</p>\n" +
         leaderboard_table(lb);
    h += "<h2>Explore</h2>\n<div id=\"filters\"></div>\n<p>The explorer shows one cell: its trajectory in 3-D (drag to orbit, scroll to "
         "zoom; the estimate aligned as ATE aligns it and coloured by its residual), a time slider that moves the camera, the RPE over "
         "time of every entry on that sequence and sensor, and the time per frame by stage. Below it, one row per entry, sequence and "
         "sensor (means over repeats): click a row to show its first successful repeat. Trajectories of more than 1500 poses are "
         "shown decimated; the filters apply to every table on the page.</p>\n<section id=\"explorer\"></section>\n" +
         cells_table(groups, view_of);
    h += "<h2>Accuracy (layout of Table 5, Kraft et al. 2016)</h2>\n<p>Mean ± std over repeats. † some repeats failed; ‡ within the ground "
         "truth's declared accuracy.</p>\n" +
         accuracy_tables(groups);
    h += "<h2>Ground truth</h2>\n<p>Declared accuracy (1σ) of each data set's ground truth (Ceriani et al. 2009): a metric at or "
         "below it (‡) cannot be told from the ground truth's own error.</p>\n<table id=\"gt\"><thead><tr><th class=\"l\">dataset</th>"
         "<th>position [m]</th><th>rotation [°]</th></tr></thead><tbody>\n";
    for (const auto& [dataset, a] : dataset_accuracies(groups))
        h += "<tr><td class=\"l\">" + html_text(dataset) + "</td><td>" + accuracy_text(a.position_m, "") + "</td><td>" +
             accuracy_text(a.rotation_deg, "") + "</td></tr>\n";
    h += "</tbody></table>\n";
    h += "<h2>Timing</h2>\n<p>Only the plugin's process() call is timed (steady clock); stages as the plugin reports them. Reading: "
         "ms per frame spent reading and decoding frames. Overhead: the rest of the frame loop's wall time.</p>\n" +
         (ctx.timing_text.empty() ? std::string() : "<p id=\"timing-protocol\">" + html_text(ctx.timing_text) + "</p>\n") +
         timing_table(groups);
    h += "<h2>Figures</h2>\n";
    // The page stays loadable for large sweeps: summary figures (entries compared, bars, RPE over time) first, then the
    // per-cell trajectories, at most kMaxEmbedded in all; every figure is in figures/ regardless.
    constexpr std::size_t kMaxEmbedded = 60;
    std::vector<const Figure*> order;
    for (const char* kind : {"compare", "boxes", "rpe_over_time", "degradation", "bars", "rpe", "traj"})
        for (const Figure& f : figures)
            if (f.drawn && f.kind == kind) order.push_back(&f);
    if (order.size() > kMaxEmbedded)
        h += fmt::format("<p>{} of {} figures shown; all are in <code>figures/</code>.</p>\n", kMaxEmbedded, order.size());
    if (order.size() > kMaxEmbedded) order.resize(kMaxEmbedded);
    for (const Figure* fp : order) {
        const Figure& f = *fp;
        h += "<figure><img alt=\"" + html_text(f.title) + "\" src=\"data:image/png;base64," +
             base64(read_binary(figure_folder / (f.stem + ".png"))) + "\"><figcaption>" + html_text(f.title) + " — <code>figures/" +
             html_text(f.stem) + ".{png,svg,pdf,dat,gp}</code></figcaption></figure>\n";
    }
    h += "<h2>Failures</h2>\n" + failures_table(lb);
    if (!ctx.problems.empty()) {
        h += "<h2 id=\"problems\">Missing or unreadable cells (this report is incomplete)</h2>\n<ul>\n";
        for (const std::string& p : ctx.problems) h += "<li>" + html_text(p) + "</li>\n";
        h += "</ul>\n";
    }
    h += "<h2>Protocol</h2>\n<pre>" + html_text(json_text(lb["context"]["protocol"])) + "</pre>\n";
    h += "<script>" + std::string(kScript) + "</script>\n";
    // The explorer opens on the best-ranked entry's first view.
    const auto initial_view = [&]() -> long {
        for (const auto& e : lb["entries"])
            if (!e["rank"].is_null() && e["rank"].get<int>() == 1)
                for (std::size_t k = 0; k < groups.size(); ++k)
                    if (view_of[k] >= 0 && groups[k].entry == e["entry"].get<std::string>()) return view_of[k];
        return 0;
    };
    h += interactive_scripts({{"kind", "report"}, {"views", views}, {"initial_view", initial_view()}});
    h += "</body></html>\n";
    return h;
}

}  // namespace vobench
