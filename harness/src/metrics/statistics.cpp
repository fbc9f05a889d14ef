#include "metrics/statistics.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vobench::metrics {

ErrorStats compute_stats(const std::vector<double>& values) {
    if (values.empty()) throw std::invalid_argument("no error values to summarise");
    ErrorStats s;
    s.count = values.size();
    const double n = static_cast<double>(s.count);
    double sum = 0, sse = 0;
    s.min = values.front();
    s.max = values.front();
    for (double v : values) {
        sum += v;
        sse += v * v;
        s.min = std::min(s.min, v);
        s.max = std::max(s.max, v);
    }
    s.sse = sse;
    s.mean = sum / n;
    s.rmse = std::sqrt(sse / n);
    double var = 0;  // two-pass, as numpy.std
    for (double v : values) var += (v - s.mean) * (v - s.mean);
    s.std = std::sqrt(var / n);
    std::vector<double> sorted = values;
    const std::size_t mid = sorted.size() / 2;
    std::nth_element(sorted.begin(), sorted.begin() + mid, sorted.end());
    s.median = sorted[mid];
    if (sorted.size() % 2 == 0) {
        const double lower = *std::max_element(sorted.begin(), sorted.begin() + mid);
        s.median = 0.5 * (lower + s.median);
    }
    return s;
}

void to_json(nlohmann::json& j, const ErrorStats& s) {
    j = nlohmann::json{{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median}, {"std", s.std},
                       {"min", s.min},   {"max", s.max},   {"sse", s.sse},       {"count", s.count}};
}

double percentile_nearest_rank(std::vector<double> values, double q) {
    if (values.empty()) throw std::invalid_argument("percentile of an empty series");
    std::sort(values.begin(), values.end());
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
    return values[std::min(values.size() - 1, rank == 0 ? 0 : rank - 1)];
}

}  // namespace vobench::metrics
