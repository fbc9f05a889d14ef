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

std::string axis_title(const metrics::MetricInfo& m) { return fmt::format("{} [{}]", what_of(m), m.unit == "deg" ? "°" : m.unit); }

}  // namespace

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
            data += gnuplot::data_label(e);
            for (const std::string& s : sensors) {
                std::vector<double> values;
                for (const RunGroup& g : groups)
                    if (g.entry == e && g.sensor == s)
                        for (const RunRecord* r : g.runs)
                            if (r->ok)
                                if (auto it = r->metrics.find(name); it != r->metrics.end()) values.push_back(it->second);
                if (values.empty()) {
                    data += " NaN NaN NaN 0";
                    continue;
                }
                any = true;
                double mean = 0;
                for (double v : values) mean += v;
                mean /= static_cast<double>(values.size());
                const auto [lo, hi] = bootstrap_mean_ci(values);
                if (mean > 0) {
                    smallest = smallest > 0 ? std::min(smallest, mean) : mean;
                    largest = std::max(largest, hi);
                }
                data += fmt::format(" {:.17g} {:.17g} {:.17g} {}", mean, lo, hi, values.size());
            }
            data += "\n";
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
            gnuplot_quoted(f.title), gnuplot_quoted(axis_title(*metric) + (log_scale ? " (log scale)" : "")), scale);
        const int width = std::clamp(360 + 70 * static_cast<int>(entries.size() * std::max<std::size_t>(1, sensors.size())), 640, 1800);
        write_file_atomic(folder / (f.stem + ".dat"), data);
        write_file_atomic(folder / (f.stem + ".gp"), gnuplot::script(f.stem, setup, plot, width, 520));
        out.push_back(f);
    }
    return out;
}

}  // namespace vobench
