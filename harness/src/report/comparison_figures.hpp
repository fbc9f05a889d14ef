// comparison_figures.hpp — a sweep's entries side by side (issue #18): one figure per ranked metric
// (ATE RMSE, RPE RMSE translation and rotation, ms per frame), every entry on one shared scale, a bar
// per entry and sensor — the mean over that entry's successful cells on that sensor (all sequences
// and repeats) — with the 95 % percentile-bootstrap interval of the mean (report/bootstrap.hpp, the
// leaderboard's method), Okabe & Ito's colour-blind-safe colours, the unit on the axis, and a legend
// only when there is more than one sensor to tell apart.
//   compare_<metric>.{png,svg,pdf,dat,gp}
// and, per sequence and sensor with two or more entries, translational and rotational RPE over time of
// the (at most five) entries with the lowest mean ATE there, on one plot:
//   rpe_over_time_<sequence>_<sensor>.*
#pragma once

#include "metrics/metric_catalog.hpp"
#include "report/aggregate.hpp"
#include "report/figures.hpp"

#include <filesystem>
#include <vector>

namespace vobench {

// A metric's axis label with its unit: "translational RPE RMSE [m]", "rotational RPE RMSE [°]".
std::string metric_axis_title(const metrics::MetricInfo& metric);

// Writes data and scripts under `folder`; drawing is the caller's (figures.cpp draws all at once).
std::vector<Figure> write_comparison_figures(const std::vector<RunGroup>& groups, const std::filesystem::path& folder);

}  // namespace vobench
