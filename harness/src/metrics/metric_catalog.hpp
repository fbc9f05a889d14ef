// metric_catalog.hpp — the one table of metric facts: every name a config, a criterion, a table, the
// leaderboard or `vobench track --json` may use, with its unit, which way is better, how a sweep
// combines it over cells, and which of the ground truth's declared accuracies it is compared with
// (Ceriani et al. 2009). configs/README.md lists the same names; a test checks that it does.
#pragma once

#include "metrics/evaluation.hpp"

#include <map>
#include <string>
#include <vector>

namespace vobench::metrics {

enum class Better { lower, higher };
enum class Combine { mean, sum };  // over an entry's cells: mean of successes, or a count summed over all
enum class GtAccuracy { none, position, rotation };

struct MetricInfo {
    std::string name;  // "ate.rmse"
    std::string unit;  // "m", "deg", "ms", "1/s", "frames", "cells"
    Better better;
    Combine combine;
    GtAccuracy accuracy;
    std::string title;  // for tables: "ATE RMSE"
};

// In a stable order: accuracy (ATE, RPE translation, RPE rotation), timing, counts.
const std::vector<MetricInfo>& metric_catalog();
// nullptr when `name` is not a metric.
const MetricInfo* find_metric(const std::string& name);
// The names, in catalogue order.
std::vector<std::string> metric_names();

// Flat metric values by catalogue name ("ate.rmse" → 0.0123).
using MetricMap = std::map<std::string, double>;
// The accuracy metrics of an evaluation, by catalogue name.
MetricMap flatten(const Evaluation& evaluation);

}  // namespace vobench::metrics
