#include "report/tables.hpp"

#include "metrics/metric_catalog.hpp"
#include "util/escape.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace vobench {

namespace {

// The columns of Table 5 (Kraft et al. 2016); units and ground-truth comparison from the catalogue.
struct Column {
    const char* metric;
    const char* title;
    int decimals;
};
const Column kAccuracy[] = {{"ate.rmse", "ATE RMSE [m]", 4},
                            {"ate.std", "ATE std [m]", 4},
                            {"rpe.trans.rmse", "RPE RMSE [m]", 4},
                            {"rpe.rot.rmse", "RPE RMSE [°]", 3}};

double gt_sigma(const RunGroup* g, const Column& c) {
    if (!g || g->runs.empty()) return 0;
    const auto& acc = g->runs.front()->cell.gt_accuracy;
    const metrics::MetricInfo* m = metrics::find_metric(c.metric);
    if (!m || m->accuracy == metrics::GtAccuracy::none) return 0;
    return m->accuracy == metrics::GtAccuracy::rotation ? acc.rotation_deg : acc.position_m;
}

std::string opt(const std::optional<double>& v, int decimals) { return v ? fmt::format("{:.{}f}", *v, decimals) : "–"; }

}  // namespace

std::string format_metric(const RunGroup* group, const std::string& metric, int decimals, double sigma) {
    if (!group) return "–";
    const auto s = summarize(*group, metric);
    if (!s) return group->failed() == group->runs.size() ? "failed" : "–";
    std::string text =
        s->n > 1 ? fmt::format("{:.{}f} ± {:.{}f}", s->mean, decimals, s->std, decimals) : fmt::format("{:.{}f}", s->mean, decimals);
    if (group->failed() > 0) text += "†";
    if (sigma > 0 && s->mean <= sigma) text += "‡";
    return text;
}

std::string accuracy_markdown(const std::vector<RunGroup>& groups) {
    std::string md;
    for (const std::string& entry : entries_of(groups)) {
        const auto sensors = sensors_of(groups, entry);
        md += fmt::format("### {}\n\n| sequence |", markdown_text(entry));
        for (const std::string& s : sensors)
            for (const Column& c : kAccuracy)  // a data set without sensor names (one camera): no sensor in the heading
                md += s.empty() ? fmt::format(" {} |", c.title) : fmt::format(" {} {} |", markdown_text(sensor_title(s)), c.title);
        md += "\n|---|";
        for (std::size_t k = 0; k < sensors.size() * std::size(kAccuracy); ++k) md += "---:|";
        md += "\n";
        for (const std::string& row : rows_of(groups, entry)) {
            md += "| " + markdown_text(row) + " |";
            for (const std::string& s : sensors) {
                const RunGroup* g = find_group(groups, entry, row, s);
                for (const Column& c : kAccuracy) md += " " + format_metric(g, c.metric, c.decimals, gt_sigma(g, c)) + " |";
            }
            md += "\n";
        }
        md += "\n";
    }
    return md;
}

std::string summary_markdown(const std::vector<RunGroup>& groups, const ReportContext& ctx) {
    std::string md = fmt::format("# {} — vobench summary\n\nGenerated {}. {}\n\n", markdown_text(ctx.name), markdown_text(ctx.generated),
                                 markdown_text(ctx.protocol_text));
    md +=
        "## Accuracy (layout of Table 5, Kraft et al. 2016)\n\n"
        "Mean ± std over repeats. † some repeats failed (see Failures); ‡ within the ground truth's declared accuracy.\n\n";
    md += accuracy_markdown(groups);
    md += "Ground truth's declared accuracy (1σ; Ceriani et al. 2009):";
    for (const auto& [dataset, a] : dataset_accuracies(groups))
        md += fmt::format(" {}: {}, {};", markdown_text(dataset), accuracy_text(a.position_m, "m"), accuracy_text(a.rotation_deg, "°"));
    md.back() = '.';
    md +=
        "\n\n## Timing (the paper's §6 terms; mean ms per frame inside the plugin's process() call)\n\n"
        "Frame reading: ms per frame spent reading and decoding, outside the timed call. Harness overhead: the rest of the frame "
        "loop's wall time (hand-over, streaming results), as a share of it.\n\n";
    if (!ctx.timing_text.empty()) md += markdown_text(ctx.timing_text) + "\n\n";
    bool cpu = false, realtime = false;
    for (const RunGroup& g : groups) {
        cpu |= timing_mean(g, "cpu_per_wall").has_value();
        for (const RunRecord* r : g.runs) realtime |= r->cell.timing.mode == "realtime";
    }
    for (const std::string& entry : entries_of(groups)) {
        const auto stages = stages_of(groups, entry);
        md += fmt::format("### {}\n\n| sequence | sensor |", markdown_text(entry));
        for (const std::string& s : stages) md += " " + markdown_text(s) + " |";
        md += " process() mean | median | p95 | max | fps | frame reading | peak RSS [MB] | harness overhead [%] |";
        if (cpu) md += " CPU/wall |";
        if (realtime) md += " dropped frames |";
        md += "\n|---|---|";
        for (std::size_t k = 0; k < stages.size() + 8 + (cpu ? 1 : 0) + (realtime ? 1 : 0); ++k) md += "---:|";
        md += "\n";
        for (const RunGroup& g : groups) {
            if (g.entry != entry) continue;
            md += fmt::format("| {} | {} |", markdown_text(g.row_label()), markdown_text(sensor_title(g.sensor)));
            for (const std::string& s : stages) md += " " + opt(stage_mean_ms(g, s), 3) + " |";
            for (const char* f : {"mean_ms", "median_ms", "p95_ms", "max_ms"}) md += " " + opt(timing_mean(g, f), 3) + " |";
            md += " " + opt(timing_mean(g, "fps"), 1) + " | " + opt(timing_mean(g, "read_ms_per_frame"), 3) + " | " +
                  opt(timing_mean(g, "peak_rss_mb"), 0) + " | " + opt(timing_mean(g, "harness_overhead_pct"), 1) + " |";
            if (cpu) md += " " + opt(timing_mean(g, "cpu_per_wall"), 2) + " |";
            if (realtime) md += " " + opt(timing_mean(g, "dropped_frames"), 1) + " |";
            md += "\n";
        }
        md += "\n";
    }
    std::string failures;
    for (const RunGroup& g : groups)
        for (const RunRecord* r : g.runs)
            if (!r->ok)
                failures +=
                    fmt::format("| {} | {} | {} | {} | {} | {} |\n", markdown_text(r->cell.id.substr(0, 12)), markdown_text(g.row_label()),
                                markdown_text(sensor_title(g.sensor)), markdown_text(g.entry), markdown_text(r->reason),
                                r->partial ? fmt::format("{} frames kept", r->run.value("frames", 0)) : "none");
    if (!failures.empty())
        md += "## Failures\n\n| cell | sequence | sensor | entry | reason | partial trajectory |\n|---|---|---|---|---|---|\n" + failures +
              "\n";
    if (!ctx.problems.empty()) {
        md += "## Missing or unreadable cells (this report is incomplete)\n\n";
        for (const std::string& p : ctx.problems) md += "- " + markdown_text(p) + "\n";
        md += "\n";
    }
    return md;
}

std::string summary_csv(const std::vector<RunGroup>& groups) {
    static const char* kMetrics[] = {"ate.rmse",       "ate.mean",     "ate.median",   "ate.std",     "ate.max",      "rpe.trans.rmse",
                                     "rpe.trans.mean", "rpe.rot.rmse", "rpe.rot.mean", "lost_frames", "failed_frames"};
    static const char* kTiming[] = {"mean_ms",      "median_ms",     "p95_ms", "max_ms", "fps", "peak_rss_mb", "harness_overhead_pct",
                                    "cpu_per_wall", "dropped_frames"};
    const auto quote = [](const std::string& s) { return csv_field(s); };
    std::string csv = "entry,algorithm,params,dataset,sequence,sensor,repeats,failed";
    for (const char* m : kMetrics) csv += fmt::format(",{0}_mean,{0}_std", m);
    for (const char* t : kTiming) csv += fmt::format(",{}", t);
    csv += "\n";
    for (const RunGroup& g : groups) {
        const Cell& c = g.runs.front()->cell;
        csv += fmt::format("{},{},{},{},{},{},{},{}", quote(g.entry), quote(c.algorithm), quote(c.variant_label()), quote(g.dataset),
                           quote(g.sequence), quote(g.sensor), g.runs.size(), g.failed());
        for (const char* m : kMetrics) {
            const auto s = summarize(g, m);
            csv += s ? fmt::format(",{:.17g},{:.17g}", s->mean, s->std) : std::string(",,");
        }
        for (const char* t : kTiming) {
            const auto v = timing_mean(g, t);
            csv += v ? fmt::format(",{:.17g}", *v) : std::string(",");
        }
        csv += "\n";
    }
    return csv;
}

namespace {

// A formatted value ("0.0123 ± 0.0004†") or already escaped text in LaTeX that pdfLaTeX also takes.
std::string latex_value(const std::string& v) {
    std::string t;
    for (std::size_t i = 0; i < v.size();) {
        if (v.compare(i, 2, "±") == 0) {
            t += "$\\pm$";
            i += 2;
        } else if (v.compare(i, 3, "†") == 0) {
            t += "$^\\dagger$";
            i += 3;
        } else if (v.compare(i, 3, "‡") == 0) {
            t += "$^\\ddagger$";
            i += 3;
        } else if (v.compare(i, 3, "–") == 0) {
            t += "--";
            i += 3;
        } else if (v.compare(i, 3, "—") == 0) {
            t += "---";
            i += 3;
        } else if (v.compare(i, 2, "Δ") == 0) {  // pdfLaTeX has no Greek in text mode
            t += "$\\Delta$";
            i += 2;
        } else if (v.compare(i, 2, "°") == 0) {
            t += "$^\\circ$";
            i += 2;
        } else
            t += v[i++];
    }
    return t;
}

// The column heads of one accuracy table: a sensor group of four per sensor.
std::string latex_head(const std::string& first, const std::vector<std::string>& sensors) {
    std::string tex = "\\begin{tabular}{l";
    for (std::size_t k = 0; k < sensors.size(); ++k) tex += "rrrr";
    tex += "}\n\\toprule\n";
    // A data set without sensor names (one camera) gets no sensor row.
    if (!(sensors.size() == 1 && sensors.front().empty())) {
        for (const std::string& s : sensors) tex += " & \\multicolumn{4}{c}{" + latex_text(sensor_title(s)) + "}";
        tex += " \\\\\n";
    }
    tex += first;
    for (std::size_t k = 0; k < sensors.size(); ++k) tex += " & ATE RMSE [m] & ATE std [m] & RPE RMSE [m] & RPE RMSE [$^\\circ$]";
    return tex + " \\\\\n\\midrule\n";
}

// The mean a comparison may call best: only a group whose every repeat succeeded.
std::optional<double> rankable_mean(const RunGroup* g, const char* metric) {
    if (!g || g->failed() > 0) return std::nullopt;
    const auto s = summarize(*g, metric);
    return s ? std::optional<double>(s->mean) : std::nullopt;
}

}  // namespace

std::string summary_latex(const std::vector<RunGroup>& groups, const ReportContext& ctx) {
    std::string tex = fmt::format("% vobench summary of '{}', generated {}. Needs \\usepackage{{booktabs}}.\n% {}\n",
                                  latex_comment(ctx.name), latex_comment(ctx.generated), latex_comment(ctx.protocol_text));
    const std::string protocol = latex_value(latex_text(ctx.protocol_text));
    const std::vector<std::string> entries = entries_of(groups);
    // Per entry, the layout of Table 5: one row per sequence.
    for (const std::string& entry : entries) {
        const auto sensors = sensors_of(groups, entry);
        tex += "\\begin{table}\n\\centering\n\\caption{" + latex_text(entry) +
               ": ATE and RPE (layout of Table 5, Kraft et al. 2016), mean $\\pm$ std over repeats. " + protocol + "}\n" +
               latex_head("Sequence", sensors);
        for (const std::string& row : rows_of(groups, entry)) {
            tex += latex_text(row);
            for (const std::string& s : sensors) {
                const RunGroup* g = find_group(groups, entry, row, s);
                for (const Column& c : kAccuracy) tex += " & " + latex_value(format_metric(g, c.metric, c.decimals, gt_sigma(g, c)));
            }
            tex += " \\\\\n";
        }
        tex += "\\bottomrule\n\\end{tabular}\n\\end{table}\n\n";
    }
    if (entries.size() < 2) return tex;
    // Per sequence, every entry side by side, the lowest mean of each column in bold (only among
    // entries whose repeats all succeeded): the table a paper compares methods with.
    std::vector<std::string> rows;
    for (const std::string& entry : entries)
        for (const std::string& row : rows_of(groups, entry))
            if (std::find(rows.begin(), rows.end(), row) == rows.end()) rows.push_back(row);
    for (const std::string& row : rows) {
        std::vector<std::string> sensors;
        for (const std::string& entry : entries)
            for (const std::string& s : sensors_of(groups, entry))
                if (find_group(groups, entry, row, s) && std::find(sensors.begin(), sensors.end(), s) == sensors.end())
                    sensors.push_back(s);
        std::sort(sensors.begin(), sensors.end());
        tex += "\\begin{table}\n\\centering\n\\caption{" + latex_text(row) +
               ": every method, mean $\\pm$ std over repeats; bold, the lowest of each column. " + protocol + "}\n" +
               latex_head("Method", sensors);
        for (const std::string& entry : entries) {
            tex += latex_text(entry);
            for (const std::string& s : sensors) {
                const RunGroup* g = find_group(groups, entry, row, s);
                for (const Column& c : kAccuracy) {
                    std::optional<double> best;
                    for (const std::string& other : entries) {
                        const auto m = rankable_mean(find_group(groups, other, row, s), c.metric);
                        if (m && (!best || *m < *best)) best = m;
                    }
                    const auto mine = rankable_mean(g, c.metric);
                    const std::string v = latex_value(format_metric(g, c.metric, c.decimals, gt_sigma(g, c)));
                    tex += " & " + (mine && best && *mine == *best ? "\\textbf{" + v + "}" : v);
                }
            }
            tex += " \\\\\n";
        }
        tex += "\\bottomrule\n\\end{tabular}\n\\end{table}\n\n";
    }
    return tex;
}

}  // namespace vobench
