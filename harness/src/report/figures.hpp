// figures.hpp — the paper's figures, drawn by gnuplot (PNG, SVG and PDF), each with its data file and
// script beside it in figures/ so that a user can restyle it for a paper:
//   rpe_<entry>_<sequence>.*   RPE over time, Kinect v1 against Kinect v2 (Kraft et al. 2016, Fig. 12)
//   traj_<entry>_<sequence>_<sensor>.*  estimate (aligned) and ground truth from above, coloured by
//                              the ATE residual (Fig. 13)
//   bars_<entry>.*             ATE and RPE RMSE per sequence and sensor (Fig. 14)
//   compare_<metric>.*         every entry side by side on one scale (report/comparison_figures.hpp)
//   boxes_<metric>.*           the spread over each entry's cells, a box per entry (report/box_figures.hpp)
//   rpe_over_time_<sequence>_<sensor>.*  RPE over time of the best entries, translation and rotation
// Every name that came from a config or plugin reaches a file name only through file_stem() (a slug
// plus a hash, so two entries never share a figure) and a script only through gnuplot_quoted().
#pragma once

#include "report/aggregate.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

struct Figure {
    std::string kind;  // "rpe", "traj", "bars", "compare", "boxes", "rpe_over_time", "degradation"
    std::string title;
    std::string stem;    // figures/<stem>.{png,svg,pdf,dat,gp}
    bool drawn = false;  // gnuplot ran and wrote the PNG
};

// Writes data and scripts under `folder` and runs gnuplot when it is installed (a warning otherwise).
std::vector<Figure> write_figures(const std::vector<RunGroup>& groups, const std::filesystem::path& folder);

}  // namespace vobench
