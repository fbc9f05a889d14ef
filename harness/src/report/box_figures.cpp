#include "report/box_figures.hpp"

#include "metrics/metric_catalog.hpp"
#include "report/comparison_figures.hpp"
#include "report/gnuplot.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace vobench {
namespace fs = std::filesystem;

namespace {

struct Box {
    std::string entry, sensor;
    std::vector<double> values;  // one per successful cell, in the records' order
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

std::vector<Figure> write_box_figures(const std::vector<RunGroup>& groups, const fs::path& folder) {
    std::vector<Figure> out;
    std::vector<std::string> sensors;
    for (const RunGroup& g : groups)
        if (std::find(sensors.begin(), sensors.end(), g.sensor) == sensors.end()) sensors.push_back(g.sensor);
    for (const char* name : {"ate.rmse", "rpe.trans.rmse", "rpe.rot.rmse"}) {
        const metrics::MetricInfo* metric = metrics::find_metric(name);
        if (!metric) continue;
        std::vector<Box> boxes;
        for (const std::string& e : entries_of(groups))
            for (const std::string& s : sensors) {
                Box box{e, s, {}};
                for (const RunGroup& g : groups)
                    if (g.entry == e && g.sensor == s)
                        for (const RunRecord* r : g.runs)
                            if (r->ok)
                                if (auto it = r->metrics.find(name); it != r->metrics.end() && std::isfinite(it->second))
                                    box.values.push_back(it->second);
                if (!box.values.empty()) boxes.push_back(std::move(box));
            }
        // A box needs a spread: with no entry of two or more cells the comparison bars say it all.
        if (boxes.empty() || std::none_of(boxes.begin(), boxes.end(), [](const Box& b) { return b.values.size() >= 2; })) continue;
        Figure f{"boxes", fmt::format("{} — spread over each entry's cells (sequences and repeats)", metric_axis_title(*metric)),
                 file_stem({"boxes", name}), false};
        std::string data, plot, tics;
        double smallest = 0, largest = 0;
        for (std::size_t k = 0; k < boxes.size(); ++k) {
            const Box& b = boxes[k];
            const std::string label = b.entry + (sensors.size() > 1 ? " (" + sensor_title(b.sensor) + ")" : "");
            data += fmt::format("# {} — {} cells\n# {}\n", clean_text(label), b.values.size(), name);
            for (double v : b.values) data += fmt::format("{:.17g}\n", v);
            data += "\n\n";
            const double m = median(b.values);
            if (m > 0) smallest = smallest > 0 ? std::min(smallest, m) : m;
            largest = std::max(largest, *std::max_element(b.values.begin(), b.values.end()));
            tics += fmt::format("{}{} {}", k ? ", " : "", gnuplot_quoted(label), k + 1);
            const std::size_t s = static_cast<std::size_t>(std::find(sensors.begin(), sensors.end(), b.sensor) - sensors.begin());
            // The legend names the sensors (once each), only when there are two or more.
            const bool first_of_sensor =
                std::none_of(boxes.begin(), boxes.begin() + static_cast<long>(k), [&](const Box& o) { return o.sensor == b.sensor; });
            const std::string title =
                sensors.size() > 1 && first_of_sensor ? "title " + gnuplot_quoted(sensor_title(b.sensor)) : std::string("notitle");
            // Each cell a point beside its box's centre, spread by the golden ratio (fixed, not random).
            plot += fmt::format(
                "{}'{}.dat' index {} using ({}):1 with boxplot lc rgb '{}' fs transparent solid 0.35 border lc rgb '{}' {}, "
                "'{}.dat' index {} using ({} + 0.3 * (($0 * 0.6180339887) - floor($0 * 0.6180339887) - 0.5)):1 with points pt 7 ps 0.45 "
                "lc rgb '#333333' notitle",
                k ? ", " : "plot ", f.stem, k, k + 1, gnuplot::colour(s), gnuplot::colour(s), title, f.stem, k, k + 1);
        }
        const bool log_scale = smallest > 0 && largest / smallest > 20;
        const std::string scale =
            log_scale ? fmt::format("set logscale y\nset yrange [{:.6g}:{:.6g}]\n", smallest / 3, largest * 2) : "set yrange [0:*]\n";
        const std::string setup = fmt::format(
            "set title {}\nset ylabel {}\nset style boxplot outliers pointtype 6\nset boxwidth 0.5\nset grid ytics\n"
            "set xtics ({}) rotate by -30 left noenhanced\nset xrange [0.3:{:.1f}]\n{}set key top left\nset rmargin 16",
            gnuplot_quoted(f.title), gnuplot_quoted(metric_axis_title(*metric) + (log_scale ? " (log scale)" : "")), tics,
            static_cast<double>(boxes.size()) + 0.7, scale);
        const int width = std::clamp(360 + 80 * static_cast<int>(boxes.size()), 640, 1800);
        write_file_atomic(folder / (f.stem + ".dat"), data);
        write_file_atomic(folder / (f.stem + ".gp"), gnuplot::script(f.stem, setup, plot, width, 520));
        out.push_back(f);
    }
    return out;
}

}  // namespace vobench
