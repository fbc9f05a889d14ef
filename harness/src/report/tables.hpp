// tables.hpp — summary.md, summary.csv and summary.tex.
//
// Accuracy in the layout of Table 5 of Kraft et al. (2016): one row per sequence, per sensor the
// ATE RMSE, ATE std, translational RPE RMSE and rotational RPE RMSE (°); one table per entry
// (algorithm + parameters). Timing in the terms of the paper's §6: mean ms per frame of each stage
// the plugin reports (put_vo: detection, clustering, tracking, depth_association, estimation), the
// whole process() call, fps, peak RSS, and the harness's overhead. Values are mean ± std over repeats.
// summary.tex adds, when there are two entries or more, one table per sequence with every entry side by
// side and the lowest mean of each column in bold (among entries whose repeats all succeeded); every
// caption names the protocol.
#pragma once

#include "report/aggregate.hpp"

#include <string>
#include <vector>

namespace vobench {

struct ReportContext {
    std::string name;           // the sweep's name
    std::string protocol_text;  // "ATE after se3 alignment; RPE at Δ = 4 f (paper protocol …)"
    std::string timing_text;    // how the times were taken (the cells' timing_protocol), "" when not recorded
    std::string rank_by = "ate.rmse";
    std::string generated;  // ISO date
    // Cells the report could not show: "<id>: missing (in cells.json, no record)" or "<id>: <why
    // the record is unsound>". Listed on every output; a report with any is incomplete.
    std::vector<std::string> problems;
};

std::string summary_markdown(const std::vector<RunGroup>& groups, const ReportContext& context);
std::string summary_csv(const std::vector<RunGroup>& groups);
std::string summary_latex(const std::vector<RunGroup>& groups, const ReportContext& context);

// The accuracy part of summary.md only (what `vobench run` prints on the terminal).
std::string accuracy_markdown(const std::vector<RunGroup>& groups);

// "0.0123", "0.0123 ± 0.0004" (n > 1), "failed", "–"; `decimals` places. Marks "‡" a value within the
// ground truth's declared accuracy (`gt_sigma` > 0).
std::string format_metric(const RunGroup* group, const std::string& metric, int decimals, double gt_sigma = 0);

}  // namespace vobench
