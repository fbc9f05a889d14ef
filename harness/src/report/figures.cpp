#include "report/figures.hpp"

#include "report/box_figures.hpp"
#include "report/comparison_figures.hpp"
#include "report/gnuplot.hpp"

#include "metrics/trajectory_io.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <vobench/plugin.hpp>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>

namespace vobench {
namespace fs = std::filesystem;

namespace {

const RunRecord* first_ok(const RunGroup* g) {
    if (!g) return nullptr;
    for (const RunRecord* r : g->runs)
        if (r->evaluation) return r;
    return nullptr;
}

void emit(std::vector<Figure>& out, const fs::path& folder, Figure f, const std::string& data, const std::string& gp) {
    write_file_atomic(folder / (f.stem + ".dat"), data);
    write_file_atomic(folder / (f.stem + ".gp"), gp);
    out.push_back(f);
}

// One gnuplot per figure, as many at once as there are cores.
void draw_all(std::vector<Figure>& figures, const fs::path& folder) {
    if (!gnuplot::available()) return;
    std::atomic<std::size_t> next{0};
    std::vector<std::thread> pool;
    for (unsigned k = 0; k < std::max(1u, std::thread::hardware_concurrency()); ++k)
        pool.emplace_back([&] {
            for (std::size_t i; (i = next++) < figures.size();) figures[i].drawn = gnuplot::run(folder, figures[i].stem);
        });
    for (std::thread& t : pool) t.join();
}

// Degradation curves (issue #20): for each filter parameter a sweep varies, a metric against the
// parameter's value, one line per algorithm entry (with the rest of its filter chain) and sensor, mean ±
// std over the cells of each point (repeats; one figure per sequence).
void degradation_figures(const std::vector<RunGroup>& groups, const fs::path& folder, std::vector<Figure>& figures) {
    // (filter, parameter, sequence) → (base entry, sensor) → value → the groups' successful runs' metrics
    using Series = std::map<std::pair<std::string, std::string>, std::map<double, std::vector<const RunRecord*>>>;
    std::map<std::tuple<std::string, std::string, std::string>, Series> curves;
    std::map<std::pair<std::string, std::string>, std::set<std::string>> values_seen;
    const auto numeric = [](const std::string& text) {
        double x;
        return vobench::sdk::parse_double(text, x);
    };
    for (const RunGroup& g : groups)
        for (const RunRecord* r : g.runs)
            if (r->ok)
                for (const CellFilter& f : r->cell.filters)
                    for (const auto& [key, text] : f.params)
                        if (numeric(text)) values_seen[{f.plugin, key}].insert(text);
    const auto varies = [&](const std::string& filter, const std::string& key) {
        const auto it = values_seen.find({filter, key});
        return it != values_seen.end() && it->second.size() >= 2;
    };
    for (const RunGroup& g : groups)
        for (const RunRecord* r : g.runs) {
            if (!r->ok) continue;
            for (std::size_t k = 0; k < r->cell.filters.size(); ++k)
                for (const auto& [key, text] : r->cell.filters[k].params) {
                    double x;
                    if (!vobench::sdk::parse_double(text, x) || !varies(r->cell.filters[k].plugin, key)) continue;
                    // One line per entry and the rest of its chain: this parameter and the ones no cell
                    // varies left out of the label.
                    std::string line = r->cell.base_entry_label();
                    for (std::size_t j = 0; j < r->cell.filters.size(); ++j)
                        for (const auto& [other, v] : r->cell.filters[j].params)
                            if ((j != k || other != key) && varies(r->cell.filters[j].plugin, other))
                                line += " " + r->cell.filters[j].plugin + " " + other + "=" + v;
                    curves[{r->cell.filters[k].plugin, key, g.row_label()}][{line, g.sensor}][x].push_back(r);
                }
        }
    for (const auto& [what, series] : curves) {
        const auto& [filter, key, row] = what;
        Figure f{"degradation", fmt::format("Degradation with {} {} — {}", filter, key, row), file_stem({"degradation", filter, key, row}),
                 false};
        std::string data, ate_plot, rpe_plot;
        int block = 0;
        for (const auto& [line, points] : series) {
            const std::string title = line.first + (line.second.empty() ? "" : " (" + sensor_title(line.second) + ")");
            data += fmt::format("# {}\n# {} ate_rmse_mean ate_rmse_std rpe_trans_rmse_mean rpe_trans_rmse_std cells\n", clean_text(title),
                                clean_text(key));
            for (const auto& [x, runs] : points) {
                std::vector<double> ate, rpe;
                for (const RunRecord* r : runs) {
                    if (auto it = r->metrics.find("ate.rmse"); it != r->metrics.end()) ate.push_back(it->second);
                    if (auto it = r->metrics.find("rpe.trans.rmse"); it != r->metrics.end()) rpe.push_back(it->second);
                }
                const auto ms = [](const std::vector<double>& v) {
                    if (v.empty()) return std::string("NaN NaN");
                    double m = 0, q = 0;
                    for (double e : v) m += e;
                    m /= static_cast<double>(v.size());
                    for (double e : v) q += (e - m) * (e - m);
                    return fmt::format("{:.9g} {:.9g}", m, v.size() > 1 ? std::sqrt(q / static_cast<double>(v.size() - 1)) : 0.0);
                };
                data += fmt::format("{:.9g} {} {} {}\n", x, ms(ate), ms(rpe), runs.size());
            }
            data += "\n\n";
            ate_plot += fmt::format("{}'{}.dat' index {} using 1:2:3 with yerrorlines lw 1.5 title {}", block ? ", " : "plot ", f.stem,
                                    block, gnuplot_quoted(title));
            rpe_plot += fmt::format("{}'{}.dat' index {} using 1:4:5 with yerrorlines lw 1.5 title {}", block ? ", " : "plot ", f.stem,
                                    block, gnuplot_quoted(title));
            ++block;
        }
        const std::string setup = fmt::format(
            "set grid\nset key outside bottom center horizontal maxrows 4 font ',8'\nset datafile missing 'NaN'\nset xlabel {}\n"
            "set yrange [0:*]\nset offsets graph 0.02, graph 0.02, 0, 0",
            gnuplot_quoted(filter + " " + key));
        const std::string plot =
            fmt::format("set multiplot layout 1,2 title {}\nset ylabel 'ATE RMSE [m]'\n{}\nset ylabel 'RPE RMSE [m]'\n{}\nunset multiplot",
                        gnuplot_quoted(f.title + " (mean ± std over cells)"), ate_plot, rpe_plot);
        emit(figures, folder, f, data, gnuplot::script(f.stem, setup, plot, 1100, 560));
    }
}

}  // namespace

std::vector<Figure> write_figures(const std::vector<RunGroup>& groups, const fs::path& folder) {
    fs::create_directories(folder);
    if (!gnuplot::available())
        spdlog::warn("gnuplot is not installed: figure data and scripts are written, not the images (apt-get install gnuplot-nox)");
    std::vector<Figure> figures;
    for (const std::string& entry : entries_of(groups)) {
        const auto sensors = sensors_of(groups, entry);
        // Fig. 12: RPE over time, one line per sensor.
        for (const std::string& row : rows_of(groups, entry)) {
            std::string data, plot;
            int block = 0;
            for (const std::string& s : sensors) {
                const RunRecord* r = first_ok(find_group(groups, entry, row, s));
                if (!r || !r->evaluation->rpe || r->evaluation->rpe->pairs.empty()) continue;
                const double t0 = r->evaluation->rpe->pairs.front().t_first;
                data += fmt::format("# {} (cell {})\n# t_s rpe_trans_m rpe_rot_deg\n", clean_text(sensor_title(s)), clean_text(r->cell.id));
                for (const auto& p : r->evaluation->rpe->pairs)
                    data += fmt::format("{:.9f} {:.9g} {:.9g}\n", p.t_first - t0, p.trans_m, p.rot_deg);
                data += "\n\n";
                // A legend only where there are sensors to tell apart.
                plot += fmt::format("{}'{}.dat' index {} using 1:2 with lines lw 1.5 {}", plot.empty() ? "plot " : ", ",
                                    file_stem({"rpe", entry, row}), block++,
                                    sensors.size() > 1 ? "title " + gnuplot_quoted(sensor_title(s)) : std::string("notitle"));
            }
            if (block == 0) continue;
            Figure f{"rpe", fmt::format("RPE over time — {} on {}", entry, row), file_stem({"rpe", entry, row}), false};
            const std::string setup =
                fmt::format("set title {}\nset xlabel 'time [s]'\nset ylabel 'translational RPE [m]'\nset grid\nset key top left",
                            gnuplot_quoted(f.title));
            emit(figures, folder, f, data, gnuplot::script(f.stem, setup, plot, 800, 400));
        }
        // Fig. 13: the path from above, coloured by the ATE residual; the two axes of largest extent.
        for (const RunGroup& g : groups) {
            if (g.entry != entry) continue;
            const RunRecord* r = first_ok(&g);
            if (!r || !r->evaluation->ate) continue;
            const auto& gt = r->evaluation->ate->ground_truth;
            const auto& est = r->evaluation->ate->aligned_estimate;
            Eigen::Vector3d lo = gt.front(), hi = gt.front();
            for (const auto& p : gt) {
                lo = lo.cwiseMin(p);
                hi = hi.cwiseMax(p);
            }
            const Eigen::Vector3d extent = hi - lo;
            int a = 0, b = 1;
            if (extent.z() > extent.x() && extent.x() <= extent.y())
                a = 2;
            else if (extent.z() > extent.y() && extent.y() < extent.x())
                b = 2;
            static const char* axis[] = {"x", "y", "z"};
            std::string data = fmt::format("# gt_{0} gt_{1} est_{0} est_{1} ate_m (cell {2})\n", axis[a], axis[b], clean_text(r->cell.id));
            for (std::size_t k = 0; k < gt.size(); ++k)
                data += fmt::format("{:.9g} {:.9g} {:.9g} {:.9g} {:.9g}\n", gt[k][a], gt[k][b], est[k][a], est[k][b],
                                    r->evaluation->ate->errors[k]);
            Figure f{"traj",
                     fmt::format("{} on {}{} — ATE RMSE {:.4f} m", entry, g.row_label(),
                                 g.sensor.empty() ? "" : " (" + sensor_title(g.sensor) + ")", r->evaluation->ate->stats.rmse),
                     file_stem({"traj", entry, g.row_label(), g.sensor}), false};
            // Equal axis scales, unless the path is nearly a line (then the plot would be a sliver).
            const bool equal = std::min(extent[a], extent[b]) > 0.15 * std::max(extent[a], extent[b]);
            const std::string setup = fmt::format(
                "set title {}\nset xlabel '{} [m]'\nset ylabel '{} [m]'\n{}set grid\nset cblabel 'ATE [m]'\n"
                "set palette defined (0 '#2c7bb6', 0.5 '#ffffbf', 1 '#d7191c')\nset key bottom right",
                gnuplot_quoted(f.title), axis[a], axis[b], equal ? "set size ratio -1\n" : "");
            const std::string plot = fmt::format(
                "plot '{0}.dat' using 1:2 with lines lc rgb '#444444' lw 2 title 'ground truth', "
                "'{0}.dat' using 3:4:5 with points pt 7 ps 0.6 palette title 'estimate (aligned)'",
                f.stem);
            emit(figures, folder, f, data, gnuplot::script(f.stem, setup, plot, 700, 600));
        }
        // Fig. 14: bars per sequence and sensor.
        std::string data = "# sequence";
        for (const std::string& s : sensors) data += fmt::format(" ate_rmse_{0} rpe_rmse_{0}", s.empty() ? "sensor" : file_stem(s));
        data += "\n";
        bool any = false;
        for (const std::string& row : rows_of(groups, entry)) {
            data += gnuplot::data_label(row);
            for (const std::string& s : sensors) {
                const RunGroup* g = find_group(groups, entry, row, s);
                const auto ate = g ? summarize(*g, "ate.rmse") : std::nullopt;
                const auto rpe = g ? summarize(*g, "rpe.trans.rmse") : std::nullopt;
                any |= ate.has_value();
                data += ate ? fmt::format(" {:.9g}", ate->mean) : " NaN";
                data += rpe ? fmt::format(" {:.9g}", rpe->mean) : " NaN";
            }
            data += "\n";
        }
        if (!any) continue;
        Figure f{"bars", fmt::format("ATE and RPE per sequence and sensor — {}", entry), file_stem({"bars", entry}), false};
        std::string ate_plot, rpe_plot;
        for (std::size_t k = 0; k < sensors.size(); ++k) {
            const std::string key = sensors.size() > 1 ? "title " + gnuplot_quoted(sensor_title(sensors[k])) : std::string("notitle");
            ate_plot += fmt::format("{}'{}.dat' using {}:xtic(1) {}", k ? ", " : "plot ", f.stem, 2 + 2 * k, key);
            rpe_plot += fmt::format("{}'{}.dat' using {}:xtic(1) {}", k ? ", " : "plot ", f.stem, 3 + 2 * k, key);
        }
        const std::string setup =
            "set style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.8 border -1\nset grid ytics\n"
            "set xtics rotate by -30\nset yrange [0:*]\nset datafile missing 'NaN'";
        const std::string plot =
            fmt::format("set multiplot layout 1,2 title {}\nset ylabel 'ATE RMSE [m]'\n{}\nset ylabel 'RPE RMSE [m]'\n{}\nunset multiplot",
                        gnuplot_quoted(f.title), ate_plot, rpe_plot);
        emit(figures, folder, f, data, gnuplot::script(f.stem, setup, plot, 1000, 420));
    }
    degradation_figures(groups, folder, figures);
    for (Figure& f : write_comparison_figures(groups, folder)) figures.push_back(std::move(f));
    for (Figure& f : write_box_figures(groups, folder)) figures.push_back(std::move(f));
    draw_all(figures, folder);
    return figures;
}

}  // namespace vobench
