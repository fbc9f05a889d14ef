// bootstrap.hpp — percentile bootstrap confidence interval of a mean (Efron & Tibshirani 1993, §13.3):
// resample the values with replacement B times, take the mean of each resample, and report the
// (1-c)/2 and (1+c)/2 quantiles of those means. Fixed seed: the same values give the same interval.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace vobench {

struct BootstrapOptions {
    int resamples = 2000;
    double confidence = 0.95;
    uint64_t seed = 1;
};

// [lo, hi]; a single value (or identical values) gives [v, v]. Throws std::invalid_argument on no values.
std::pair<double, double> bootstrap_mean_ci(const std::vector<double>& values, const BootstrapOptions& options = {});

}  // namespace vobench
