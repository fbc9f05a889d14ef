// box_figures.hpp — the spread of each entry's results (issue #18, item 1; rpg_trajectory_evaluation's
// and evo_res's box plots): per ranked accuracy metric, one box per entry and sensor over all its
// successful cells — every sequence and repeat — with each cell's value drawn over it as a point, every
// entry on one shared scale (logarithmic when the medians span more than 20×). Boxes: median, the
// quartiles, whiskers to the farthest value within 1.5 interquartile ranges (Tukey), values beyond as
// outliers; gnuplot's `boxplot` style computes them from the data file, where the values are.
//   boxes_<metric>.{png,svg,pdf,dat,gp}
#pragma once

#include "report/aggregate.hpp"
#include "report/figures.hpp"

#include <filesystem>
#include <vector>

namespace vobench {

// Writes data and scripts under `folder`; drawing is the caller's (figures.cpp draws all at once).
std::vector<Figure> write_box_figures(const std::vector<RunGroup>& groups, const std::filesystem::path& folder);

}  // namespace vobench
