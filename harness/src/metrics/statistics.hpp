// statistics.hpp — the summary statistics the TUM scripts print with --verbose (numpy semantics:
// population standard deviation, median averaging the two middle values of an even count).
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <vector>

namespace vobench::metrics {

struct ErrorStats {
    double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0, sse = 0;
    std::size_t count = 0;
};

// Throws std::invalid_argument on an empty series.
ErrorStats compute_stats(const std::vector<double>& values);

void to_json(nlohmann::json& j, const ErrorStats& s);

// The nearest-rank q-quantile (0 < q <= 1): the smallest value with at least q of the series at or
// below it. Throws std::invalid_argument on an empty series.
double percentile_nearest_rank(std::vector<double> values, double q);

}  // namespace vobench::metrics
