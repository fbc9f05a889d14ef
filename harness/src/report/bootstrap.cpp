#include "report/bootstrap.hpp"

#include "metrics/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace vobench {

std::pair<double, double> bootstrap_mean_ci(const std::vector<double>& values, const BootstrapOptions& o) {
    if (values.empty()) throw std::invalid_argument("bootstrap of no values");
    if (o.resamples < 1 || !(o.confidence > 0 && o.confidence < 1))
        throw std::invalid_argument("bootstrap: resamples >= 1 and 0 < confidence < 1");
    std::mt19937_64 rng(o.seed);
    std::uniform_int_distribution<std::size_t> pick(0, values.size() - 1);
    std::vector<double> means(static_cast<std::size_t>(o.resamples));
    for (double& m : means) {
        double sum = 0;
        for (std::size_t k = 0; k < values.size(); ++k) sum += values[pick(rng)];
        m = sum / static_cast<double>(values.size());
    }
    const double alpha = (1.0 - o.confidence) / 2.0;
    return {metrics::percentile_nearest_rank(means, alpha), metrics::percentile_nearest_rank(means, 1.0 - alpha)};
}

}  // namespace vobench
