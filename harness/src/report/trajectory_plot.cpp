#include "report/trajectory_plot.hpp"

#include "report/interactive_page.hpp"
#include "report/trajectory_view.hpp"

#include "metrics/ate.hpp"
#include "report/gnuplot.hpp"
#include "util/escape.hpp"
#include "util/files.hpp"

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <regex>
#include <stdexcept>

namespace vobench {
namespace fs = std::filesystem;

namespace {

struct Row {
    double t;
    Eigen::Vector3d p, rpy_deg;
};

// R = Rz(yaw) Ry(pitch) Rx(roll), as evo and ROS give roll, pitch and yaw.
Eigen::Vector3d roll_pitch_yaw_deg(const Eigen::Matrix3d& R) {
    const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
    const double roll = std::atan2(R(2, 1), R(2, 2)), yaw = std::atan2(R(1, 0), R(0, 0));
    return Eigen::Vector3d(roll, pitch, yaw) * (180.0 / M_PI);
}

std::vector<Row> plotted_rows(const metrics::Trajectory& poses, const metrics::Alignment& a, double t0) {
    std::vector<Row> rows;
    for (const metrics::StampedPose& s : poses) rows.push_back({s.t - t0, a.apply(s.p), roll_pitch_yaw_deg(a.R * s.q.toRotationMatrix())});
    return rows;
}

// One gnuplot data block: t x y z roll pitch yaw speed (speed at the later pose of each step; the
// first pose's is left out with '?', gnuplot's missing value).
std::string block(const std::string& label, const std::vector<Row>& rows) {
    std::string out = "# " + clean_text(label) + "\n# t_s x_m y_m z_m roll_deg pitch_deg yaw_deg speed_mps\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        std::string speed = "?";
        if (i > 0 && rows[i].t > rows[i - 1].t)
            speed = fmt::format("{:.17g}", (rows[i].p - rows[i - 1].p).norm() / (rows[i].t - rows[i - 1].t));
        out += fmt::format("{:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {}\n", rows[i].t, rows[i].p.x(), rows[i].p.y(),
                           rows[i].p.z(), rows[i].rpy_deg.x(), rows[i].rpy_deg.y(), rows[i].rpy_deg.z(), speed);
    }
    return out + "\n\n";
}

std::string legend(const PlottedTrajectory& line, bool reference, metrics::AlignmentMethod method) {
    if (reference) return line.label + " (reference)";
    if (line.ate_rmse_m < 0) return line.label;
    return fmt::format("{} ({}, ATE {:.4f} m)", line.label, metrics::alignment_name(method), line.ate_rmse_m);
}

// The plot commands of one panel: `columns` the using spec, `splot` for 3-D.
std::string panel(const std::string& stem, const std::vector<std::string>& titles, bool with_reference, const std::string& columns,
                  bool splot, bool keys) {
    std::string cmd = splot ? "splot " : "plot ";
    for (std::size_t k = 0; k < titles.size(); ++k) {
        const bool ref = with_reference && k == 0;
        const std::string style =
            ref ? "lc rgb '#000000' dt 2 lw 1.5" : fmt::format("lc rgb '{}' lw 1.5", gnuplot::colour(k - (with_reference ? 1 : 0)));
        cmd += fmt::format("{}'{}.dat' index {} using {} with lines {} {}", k ? ", " : "", stem, k, columns, style,
                           keys ? "title " + gnuplot_quoted(titles[k]) : std::string("notitle"));
    }
    return cmd + "\n";
}

// Umeyama's rotation comes from the spread of the matched positions: a trajectory that is nearly a
// point or a line (fr1/rpy turns on the spot) leaves rotations about it undetermined.
std::string spread_warning(const std::vector<Eigen::Vector3d>& positions, metrics::AlignmentMethod method) {
    if (method == metrics::AlignmentMethod::None || positions.size() < 3) return "";
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : positions) mean += p;
    mean /= static_cast<double>(positions.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (const Eigen::Vector3d& p : positions) covariance += (p - mean) * (p - mean).transpose();
    covariance /= static_cast<double>(positions.size());
    const Eigen::Vector3d rms = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues().cwiseMax(0).cwiseSqrt();
    if (rms(1) >= 0.05) return "";  // eigenvalues ascending: rms(1) is the second largest spread
    return fmt::format(
        "the matched reference positions spread {:.3f} m and {:.3f} m across their main direction: the {} "
        "alignment's rotation is poorly determined, and so are the orientations drawn (rpy)",
        rms(1), rms(0), metrics::alignment_name(method));
}

}  // namespace

PlotMode parse_plot_mode(const std::string& name) {
    if (name == "xy") return PlotMode::Xy;
    if (name == "xz") return PlotMode::Xz;
    if (name == "xyz") return PlotMode::Xyz;
    if (name == "rpy") return PlotMode::Rpy;
    if (name == "speed") return PlotMode::Speed;
    throw std::invalid_argument("unknown plot mode '" + name + "' (xy, xz, xyz, rpy or speed)");
}

TrajectoryPlot write_trajectory_plot(const std::optional<PlotInput>& reference, const std::vector<PlotInput>& estimates,
                                     const PlotOptions& options, const fs::path& out) {
    if (estimates.empty() && !reference) throw std::invalid_argument("nothing to plot: give at least one trajectory");
    const std::string extension = out.extension().string();
    if (extension != ".png" && extension != ".svg" && extension != ".pdf" && extension != ".html")
        throw std::invalid_argument(out.string() + ": the figure must end .png, .svg, .pdf or .html");
    const std::string stem = out.stem().string();
    // The stem is written into the script between quotes: plain characters only.
    if (!std::regex_match(stem, std::regex("[A-Za-z0-9._+-]{1,100}")))
        throw std::invalid_argument(out.string() + ": choose a plain file name (letters, digits, . _ + -) for the figure");
    const fs::path folder = out.has_parent_path() ? out.parent_path() : fs::path(".");
    fs::create_directories(folder);

    TrajectoryPlot plot;
    plot.image = out;
    std::string data;
    std::vector<std::string> titles;
    const double t0 = reference && !reference->poses.empty()                   ? reference->poses.front().t
                      : !estimates.empty() && !estimates.front().poses.empty() ? estimates.front().poses.front().t
                                                                               : 0.0;
    if (reference) {
        PlottedTrajectory line{reference->label, reference->poses.size(), 0, -1, {}, ""};
        data += block(reference->label, plotted_rows(reference->poses, line.alignment, t0));
        titles.push_back(legend(line, true, options.alignment));
        plot.lines.push_back(line);
    }
    for (const PlotInput& e : estimates) {
        PlottedTrajectory line{e.label, e.poses.size(), 0, -1, {}, ""};
        if (reference) {
            metrics::AteOptions ate;
            ate.association = options.association;
            ate.alignment = options.alignment;
            try {
                const metrics::AteResult r = metrics::compute_ate(reference->poses, e.poses, ate);
                line.alignment = r.alignment;
                line.matched = r.association.matches.size();
                line.ate_rmse_m = r.stats.rmse;
                line.warning = spread_warning(r.ground_truth, options.alignment);
            } catch (const std::exception& ex) {
                throw std::runtime_error(e.label + ": cannot be aligned to " + reference->label + ": " + ex.what());
            }
        }
        data += block(e.label, plotted_rows(e.poses, line.alignment, t0));
        titles.push_back(legend(line, false, options.alignment));
        plot.lines.push_back(line);
    }

    if (extension == ".html") {  // the interactive variant: one page, no gnuplot
        std::string title = "vobench plot:";
        for (const PlottedTrajectory& line : plot.lines) title += " " + line.label;
        write_trajectory_page(trajectories_view(reference, estimates, plot.lines), title, out);
        plot.drawn = true;
        return plot;
    }
    const bool ref = reference.has_value();
    // One legend entry a line below the plot, left-aligned text: long titles are never clipped.
    std::string setup = "set grid\nset key outside bottom center vertical Left reverse\n";
    std::string body;
    switch (options.mode) {
        case PlotMode::Xy:
            setup += "set size ratio -1\nset xtics rotate by 45 right\nset xlabel 'x [m]'\nset ylabel 'y [m]'\n";
            body = panel(stem, titles, ref, "2:3", false, true);
            break;
        case PlotMode::Xz:
            setup += "set size ratio -1\nset xtics rotate by 45 right\nset xlabel 'x [m]'\nset ylabel 'z [m]'\n";
            body = panel(stem, titles, ref, "2:4", false, true);
            break;
        case PlotMode::Xyz:
            setup +=
                "set view 60,30,1.1\nset view equal xy\nset xtics rotate by 45 right\nset xlabel 'x [m]' offset 0,-1\n"
                "set ylabel 'y [m]'\nset zlabel 'z [m]' rotate parallel\nset ticslevel 0\n";
            body = panel(stem, titles, ref, "2:3:4", true, true);
            break;
        case PlotMode::Rpy:
            setup += "set xlabel 't [s]'\n";
            body = "set multiplot layout 3,1\nset ylabel 'roll [°]'\nunset xlabel\n" + panel(stem, titles, ref, "1:5", false, false) +
                   "set ylabel 'pitch [°]'\n" + panel(stem, titles, ref, "1:6", false, false) +
                   "set ylabel 'yaw [°]'\nset xlabel 't [s]'\n" + panel(stem, titles, ref, "1:7", false, true) + "unset multiplot\n";
            break;
        case PlotMode::Speed:
            setup += "set xlabel 't [s]'\nset ylabel 'speed [m/s]'\n";
            body = panel(stem, titles, ref, "1:8", false, true);
            break;
    }
    const int height = options.mode == PlotMode::Rpy ? options.height * 3 / 2 : options.height;
    write_file_atomic(folder / (stem + ".dat"), data);
    write_file_atomic(folder / (stem + ".gp"), gnuplot::script(stem, setup, body, options.width, height));
    plot.drawn = gnuplot::available() && gnuplot::run(folder, stem);
    return plot;
}

}  // namespace vobench
