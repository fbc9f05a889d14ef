// leaderboard.hpp — leaderboard.json, schema version 1 (schemas/leaderboard.schema.json).
//
// One entry per algorithm + parameters, with every cell's metrics, aggregates (mean, std and a 95 %
// bootstrap interval over the entry's successful cells), a rank by the primary metric, ties (entries
// whose intervals overlap: the difference is within noise), criteria pass/fail, and the failures.
// Entries with a failed cell are not ranked: an average over the cells that happened to work would
// flatter them.
#pragma once

#include "record/criterion.hpp"
#include "report/aggregate.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace vobench {

constexpr const char* kLeaderboardSchemaVersion = "1.0.0";

struct LeaderboardContext {
    std::string name;
    std::string rank_by = "ate.rmse";
    std::vector<Criterion> criteria;
    nlohmann::json protocol;  // protocol_json of the cells
    std::string generated;    // ISO date
};

// True when a larger value is better (fps), false for errors and counts.
bool higher_is_better(const std::string& metric);

nlohmann::json build_leaderboard(const std::vector<RunRecord>& records, const LeaderboardContext& context);

// The value a criterion is checked on: counts (lost_frames, failed_frames, failed_cells) summed over
// the entry's cells, other metrics averaged over its successful cells. nullopt when unavailable.
std::optional<double> criterion_value(const std::vector<const RunRecord*>& cells, const std::string& metric);
bool criterion_holds(const Criterion& c, double value);

}  // namespace vobench
