#include "report/comparison_figures.hpp"

#include "metrics/metric_catalog.hpp"
#include "report/bootstrap.hpp"
#include "report/gnuplot.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace vobench {
namespace fs = std::filesystem;

namespace {

const char* const kCompared[] = {"ate.rmse", "rpe.trans.rmse", "rpe.rot.rmse", "ms_per_frame"};

// The catalogue's titles are for tables with a unit column ("RPE RMSE" twice); a figure says which.
std::string what_of(const metrics::MetricInfo& m) {
    if (m.name == "rpe.trans.rmse") return "translational RPE RMSE";
    if (m.name == "rpe.rot.rmse") return "rotational RPE RMSE";
    return m.title;
}

// RPE over time of the best entries on one sequence and sensor: translation and rotation, one line an
// entry (its first successful cell), the entries ranked by their mean ATE RMSE there.
constexpr std::size_t kTopEntries = 5;

void rpe_over_time(const std::vector<RunGroup>& groups, const std::vector<std::string>& entries, const std::string& row,
                   const std::string& sensor, const fs::path& folder, std::vector<Figure>& out) {
    struct Candidate {
        double ate;
        std::string entry;
        const RunRecord* run;
    };
    std::vector<Candidate> candidates;
    for (const std::string& e : entries) {
        const RunGroup* g = find_group(groups, e, row, sensor);
        if (!g) continue;
        const auto ate = summarize(*g, "ate.rmse");
        for (const RunRecord* r : g->runs)
            if (r->ok && r->evaluation && r->evaluation->rpe && !r->evaluation->rpe->pairs.empty()) {
                candidates.push_back({ate ? ate->mean : 1e300, e, r});
                break;
            }
    }
    if (candidates.size() < 2) return;  // one entry: its own figure (rpe_<entry>_…) already shows it
    std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.ate < b.ate; });
    if (candidates.size() > kTopEntries) candidates.resize(kTopEntries);
    Figure f{"rpe_over_time",
             fmt::format("RPE over time on {} ({}) — the {} entries of lowest ATE", row, sensor_title(sensor), candidates.size()),
             file_stem({"rpe_over_time", row, sensor}), false};
    std::string data, trans, rot;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        const auto& pairs = candidates[k].run->evaluation->rpe->pairs;
        data += fmt::format("# {} (cell {})\n# t_s rpe_trans_m rpe_rot_deg\n", clean_text(candidates[k].entry),
                            clean_text(candidates[k].run->cell.id));
        for (const auto& p : pairs)
            data += fmt::format("{:.9f} {:.17g} {:.17g}\n", p.t_first - pairs.front().t_first, p.trans_m, p.rot_deg);
        data += "\n\n";
        const std::string style = fmt::format("with lines lw 1.5 lc rgb '{}'", gnuplot::colour(k));
        // The legend once, beside the upper panel.
        trans += fmt::format("{}'{}.dat' index {} using 1:2 {} title {}", k ? ", " : "plot ", f.stem, k, style,
                             gnuplot_quoted(candidates[k].entry));
        rot += fmt::format("{}'{}.dat' index {} using 1:3 {} notitle", k ? ", " : "plot ", f.stem, k, style);
    }
    const std::string setup = "set grid\nset key outside right top vertical Left reverse noenhanced\nset xlabel 'time [s]'";
    const std::string plot = fmt::format(
        "set multiplot layout 2,1 title {}\nset ylabel 'translational RPE [m]'\n{}\n"
        "set ylabel 'rotational RPE [°]'\n{}\nunset multiplot",
        gnuplot_quoted(f.title), trans, rot);
    write_file_atomic(folder / (f.stem + ".dat"), data);
    write_file_atomic(folder / (f.stem + ".gp"), gnuplot::script(f.stem, setup, plot, 1100, 700));
    out.push_back(f);
}

}  // namespace

std::string metric_axis_title(const metrics::MetricInfo& m) { return fmt::format("{} [{}]", what_of(m), m.unit == "deg" ? "°" : m.unit); }

std::vector<Figure> write_comparison_figures(const std::vector<RunGroup>& groups, const fs::path& folder) {
    std::vector<Figure> out;
    const std::vector<std::string> entries = entries_of(groups);
    std::vector<std::string> sensors;
    for (const std::string& e : entries)
        for (const std::string& s : sensors_of(groups, e))
            if (std::find(sensors.begin(), sensors.end(), s) == sensors.end()) sensors.push_back(s);
    if (entries.empty()) return out;
    for (const char* name : kCompared) {
        const metrics::MetricInfo* metric = metrics::find_metric(name);
        if (!metric) continue;
        std::string data = "# entry";
        for (const std::string& s : sensors)
            data += fmt::format(" mean_{0} ci95_lo_{0} ci95_hi_{0} cells_{0}", file_stem(s.empty() ? "sensor" : s));
        data += "\n";
        bool any = false;
        double smallest = 0, largest = 0;  // of the positive means
        for (const std::string& e : entries) {
            std::string row;
            bool has_value = false;
            for (const std::string& s : sensors) {
                std::vector<double> values;
                for (const RunGroup& g : groups)
                    if (g.entry == e && g.sensor == s)
                        for (const RunRecord* r : g.runs)
                            if (r->ok)
                                if (auto it = r->metrics.find(name); it != r->metrics.end()) values.push_back(it->second);
                if (values.empty()) {
                    row += " NaN NaN NaN 0";
                    continue;
                }
                any = has_value = true;
                double mean = 0;
                for (double v : values) mean += v;
                mean /= static_cast<double>(values.size());
                const auto [lo, hi] = bootstrap_mean_ci(values);
                if (mean > 0) {
                    smallest = smallest > 0 ? std::min(smallest, mean) : mean;
                    largest = std::max(largest, hi);
                }
                row += fmt::format(" {:.17g} {:.17g} {:.17g} {}", mean, lo, hi, values.size());
            }
            // An entry without a value keeps its place on the axis and says why it has no bar.
            data += gnuplot::data_label(has_value ? e : e + " (no result)") + row + "\n";
        }
        if (!any) continue;
        Figure f{"compare", fmt::format("{} — every entry, mean over its cells with the 95 % bootstrap interval", what_of(*metric)),
                 file_stem({"compare", name}), false};
        std::string plot;
        for (std::size_t k = 0; k < sensors.size(); ++k)
            plot += fmt::format("{}'{}.dat' using {}:{}:{}:xtic(1) lc rgb '{}' {}", k ? ", " : "plot ", f.stem, 2 + 4 * k, 3 + 4 * k,
                                4 + 4 * k, gnuplot::colour(k),
                                sensors.size() > 1 ? "title " + gnuplot_quoted(sensor_title(sensors[k])) : std::string("notitle"));
        // One scale for every entry: linear, unless the means span more than 20× (a baseline that
        // does not track beside ones that do), when a linear axis would flatten the good entries.
        const bool log_scale = smallest > 0 && largest / smallest > 20;
        const std::string scale =
            log_scale ? fmt::format("set logscale y\nset yrange [{:.6g}:{:.6g}]\n", smallest / 3, largest * 2) : "set yrange [0:*]\n";
        const std::string setup = fmt::format(
            "set title {}\nset ylabel {}\nset style data histograms\nset style histogram errorbars gap 1.5 lw 1.2\n"
            "set style fill solid 0.85 border -1\nset grid ytics\nset xtics rotate by -30 left noenhanced\n{}"
            "set datafile missing 'NaN'\nset key top left\nset rmargin 16",
            gnuplot_quoted(f.title), gnuplot_quoted(metric_axis_title(*metric) + (log_scale ? " (log scale)" : "")), scale);
        const int width = std::clamp(360 + 70 * static_cast<int>(entries.size() * std::max<std::size_t>(1, sensors.size())), 640, 1800);
        write_file_atomic(folder / (f.stem + ".dat"), data);
        write_file_atomic(folder / (f.stem + ".gp"), gnuplot::script(f.stem, setup, plot, width, 520));
        out.push_back(f);
    }
    std::vector<std::string> rows;
    for (const RunGroup& g : groups)
        if (std::find(rows.begin(), rows.end(), g.row_label()) == rows.end()) rows.push_back(g.row_label());
    for (const std::string& row : rows)
        for (const std::string& s : sensors) rpe_over_time(groups, entries, row, s, folder, out);
    return out;
}

}  // namespace vobench
