// trajectory_plot.hpp — `vobench plot`: evo_traj-style figures of any trajectories (every format
// `eval` reads), each estimate aligned to the reference with the metrics' own association and
// alignment — the very transform its ATE uses — drawn by gnuplot as PNG, SVG and PDF with the data
// and script beside them (report/gnuplot.hpp).
//
// Modes: xy, xz (from above, from the side: equal axes), xyz (3-D), rpy (roll, pitch, yaw over time:
// R = Rz(yaw) Ry(pitch) Rx(roll), degrees), speed (m/s over time, from consecutive positions).
#pragma once

#include "metrics/alignment.hpp"
#include "metrics/association.hpp"
#include "metrics/pose.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace vobench {

enum class PlotMode { Xy, Xz, Xyz, Rpy, Speed };
PlotMode parse_plot_mode(const std::string& name);  // throws std::invalid_argument naming the modes

struct PlotInput {
    std::string label;  // the legend's text (the file name by default)
    metrics::Trajectory poses;
};

struct PlotOptions {
    PlotMode mode = PlotMode::Xy;
    metrics::AlignmentMethod alignment = metrics::AlignmentMethod::Se3;
    metrics::AssociationOptions association;
    int width = 800, height = 640;  // pixels; the PDF at 100 px an inch
};

struct PlottedTrajectory {
    std::string label;
    std::size_t poses = 0, matched = 0;  // matched: pairs with the reference (0 without one)
    double ate_rmse_m = -1;              // after alignment; −1 without a reference
    metrics::Alignment alignment;        // applied to every pose of the estimate
    // Set when the matched reference positions hardly span two directions (second principal RMS under
    // 5 cm): the alignment's rotation is then poorly determined, and so are the drawn orientations.
    std::string warning;
};

struct TrajectoryPlot {
    std::vector<PlottedTrajectory> lines;  // the reference first, when there is one
    std::filesystem::path image;           // <out>; .png, .svg and .pdf are all written
    bool drawn = false;                    // gnuplot ran; data and script are written either way
};

// `out`: the figure's file, ending .png, .svg or .pdf (all three are drawn), or .html (an interactive
// page: report/interactive_page.hpp); its name (not its folder) must be a plain file
// name (letters, digits, . _ + -), as it goes into the script. Throws std::invalid_argument for a bad
// name or no estimate, std::runtime_error naming the estimate when it cannot be aligned.
TrajectoryPlot write_trajectory_plot(const std::optional<PlotInput>& reference, const std::vector<PlotInput>& estimates,
                                     const PlotOptions& options, const std::filesystem::path& out);

}  // namespace vobench
