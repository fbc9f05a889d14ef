// trajectory_view.hpp — what the interactive page (report/interactive_page.hpp) draws, as JSON:
// a "view" is one 3-D scene of tracks (positions, orientations for the camera frusta, stamps, and the
// ATE residual where there is one), with the cell's RPE over time and its per-frame timing. Long
// series are decimated for display (every k-th pose, always the last; timing as bucket means) and the
// view says so ("decimated"); the metrics are never computed from these numbers.
#pragma once

#include "record/run_record.hpp"
#include "report/trajectory_plot.hpp"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <vector>

namespace vobench {

struct ViewLimits {
    std::size_t max_poses = 1500;        // per track
    std::size_t max_rpe_pairs = 1500;    // per cell
    std::size_t max_timing_rows = 1000;  // per cell (bucket means beyond)
};

// Indices 0, k, 2k, … and n − 1 with k = ⌈n / max⌉; all of them when n ≤ max.
std::vector<std::size_t> display_indices(std::size_t n, std::size_t max);

// A report cell's view: ground truth and the aligned estimate as ATE paired them, the RPE pairs, and
// runs/<id>/timing.csv (or "timing_error" naming what is wrong with it). `run.evaluation` must hold
// an ATE; nullopt otherwise.
std::optional<nlohmann::json> cell_view(const RunRecord& run, const ViewLimits& limits = {});

// `vobench plot`'s view: the reference and each estimate with the alignment its line carries.
nlohmann::json trajectories_view(const std::optional<PlotInput>& reference, const std::vector<PlotInput>& estimates,
                                 const std::vector<PlottedTrajectory>& lines, const ViewLimits& limits = {});

}  // namespace vobench
