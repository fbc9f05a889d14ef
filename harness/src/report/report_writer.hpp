// report_writer.hpp — everything under a sweep's output folder that is derived from runs/: summary.md,
// summary.csv, summary.tex, leaderboard.json, figures/, report.html. `vobench run` calls it at the end;
// `vobench report DIR` calls it alone. sweep.json (written by `vobench run`) supplies the sweep's
// name, ranking metric and criteria; without it the defaults apply.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace vobench {

struct ReportResult {
    std::size_t runs = 0, failed = 0;
    std::string accuracy_markdown;             // for the terminal
    std::vector<std::string> failed_required;  // "entry: criterion" for each required criterion not met
    std::vector<std::string> problems;         // cells missing or unsound (load_runs): the report is incomplete
};

// Throws std::runtime_error when there is no sound record at all.
// `re_evaluate`: every cell's metrics recomputed from its trajectory (record/run_record.hpp LoadOptions).
ReportResult write_report(const std::filesystem::path& out, bool re_evaluate = false);

// One sentence naming the evaluation protocol a cell's protocol JSON (metrics::protocol_json)
// describes, with its parameters and the reference that defines it; "" for no protocol.
std::string protocol_text(const nlohmann::json& protocol);

}  // namespace vobench
