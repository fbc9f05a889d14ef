// vobench plot [--ref FILE] EST... — trajectories drawn as evo_traj draws them (report/trajectory_plot.hpp).
#include "cli/commands.hpp"
#include "report/trajectory_plot.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <iostream>

namespace vobench::cli {
namespace {

// Frame-indexed stamps (kitti, putk2-raw) in seconds: index / rate.
void rescale_stamps(metrics::Trajectory& t, double rate) {
    for (metrics::StampedPose& p : t) p.t /= rate;
}

}  // namespace

void add_plot_command(CLI::App& app, int& exit_code) {
    auto* c = app.add_subcommand("plot", "Draw trajectories (any format eval reads), aligned to a reference as ATE aligns them");
    static std::string ref, ref_format = "tum", out = "trajectories.pdf", mode = "xy", align = "se3";
    static std::vector<std::string> estimates, formats, labels;
    static double max_diff = 0.02, offset = 0, index_rate = 0;
    c->add_option("ESTIMATES", estimates, "Trajectory files to draw")->check(CLI::ExistingFile);
    c->add_option("--ref", ref, "Reference (ground truth): drawn dashed, every estimate aligned to it")->check(CLI::ExistingFile);
    c->add_option("--ref-format", ref_format, "tum, kitti, euroc or putk2-raw")->capture_default_str();
    c->add_option("--format", formats, "Each estimate's format, in order (one value: all); tum, kitti, euroc or putk2-raw");
    c->add_option("--label", labels, "Each estimate's legend text, in order (default: the file name)");
    c->add_option("--align", align, "se3, sim3, posyaw or none")->capture_default_str();
    c->add_option("--mode", mode, "xy, xz, xyz, rpy or speed")->capture_default_str();
    c->add_option("--out", out,
                  "The figure: FILE.png, .svg or .pdf (all three are written, with FILE.dat and FILE.gp), or FILE.html (interactive, 3-D)")
        ->capture_default_str();
    c->add_option("--max-diff", max_diff, "Association: largest stamp difference, seconds")->capture_default_str();
    c->add_option("--offset", offset, "Association: seconds added to the estimates' stamps")->capture_default_str();
    c->add_option("--index-rate", index_rate, "kitti and putk2-raw files (stamps are frame indices): frames per second");
    c->callback([&exit_code] {
        if (estimates.empty() && ref.empty()) throw std::invalid_argument("plot: give trajectory files (and --ref for a reference)");
        if (formats.size() > 1 && formats.size() != estimates.size())
            throw std::invalid_argument(
                fmt::format("plot: {} --format values for {} estimates (give one, or one each)", formats.size(), estimates.size()));
        if (labels.size() > estimates.size()) throw std::invalid_argument("plot: more --label values than estimates");
        auto load = [](const std::string& path, const std::string& format, const std::string& label) {
            PlotInput in{label.empty() ? std::filesystem::path(path).filename().string() : label, load_trajectory_file(path, format)};
            if (index_rate > 0 && (format == "kitti" || format == "putk2-raw")) rescale_stamps(in.poses, index_rate);
            return in;
        };
        PlotOptions options;
        options.mode = parse_plot_mode(mode);
        options.alignment = metrics::parse_alignment(align);
        options.association.max_difference = max_diff;
        options.association.offset = offset;
        std::optional<PlotInput> reference;
        if (!ref.empty()) reference = load(ref, ref_format, "");
        std::vector<PlotInput> inputs;
        for (std::size_t k = 0; k < estimates.size(); ++k)
            inputs.push_back(
                load(estimates[k], formats.empty() ? "tum" : formats[formats.size() == 1 ? 0 : k], k < labels.size() ? labels[k] : ""));
        const TrajectoryPlot plot = write_trajectory_plot(reference, inputs, options, out);
        for (const PlottedTrajectory& line : plot.lines) {
            if (!line.warning.empty()) spdlog::warn("{}: {}", line.label, line.warning);
            if (line.ate_rmse_m >= 0)
                std::cout << fmt::format("{}: {} poses, {} matched, ATE {:.6f} m after {} alignment (scale {:.6f})\n", line.label,
                                         line.poses, line.matched, line.ate_rmse_m, align, line.alignment.scale);
            else
                std::cout << fmt::format("{}: {} poses\n", line.label, line.poses);
        }
        const std::filesystem::path stem = plot.image.parent_path() / plot.image.stem();
        if (plot.drawn && plot.image.extension() == ".html") {
            std::cout << "Page: " << plot.image.string() << " (interactive; self-contained, works offline)\n";
            exit_code = 0;
        } else if (plot.drawn) {
            std::cout << "Figure: " << stem.string() << ".{png,svg,pdf} (data and script: .dat, .gp)\n";
            exit_code = 0;
        } else {
            spdlog::error("gnuplot did not draw the figure (apt-get install gnuplot-nox); data and script: {}.dat, {}.gp", stem.string(),
                          stem.string());
            exit_code = 1;
        }
    });
}

}  // namespace vobench::cli
