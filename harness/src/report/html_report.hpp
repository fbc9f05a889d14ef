// html_report.hpp — report.html: one self-contained page (no network: styles, script and figures
// inline, figures as PNG data) with the sortable leaderboard, the Table 5-style accuracy tables, the
// timing table, the figures, the failures with their reasons, and the protocol. Every string that came
// from a config or a plugin goes through html_text() (util/escape.hpp).
#pragma once

#include "report/aggregate.hpp"
#include "report/figures.hpp"
#include "report/tables.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

std::string render_html_report(const std::vector<RunGroup>& groups, const nlohmann::json& leaderboard, const std::vector<Figure>& figures,
                               const std::filesystem::path& figure_folder, const ReportContext& context);

}  // namespace vobench
