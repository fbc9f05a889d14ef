#include "metrics/association.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace vobench::metrics {

Association associate(const std::vector<double>& first, const std::vector<double>& second, const AssociationOptions& options) {
    struct Candidate {
        double diff;
        std::size_t a, b;
    };
    std::vector<Candidate> candidates;
    candidates.reserve(second.size() * 2);
    // The window is searched with a margin and filtered with the script's exact expression, so that
    // rounding at the window's edge cannot change which pairs qualify.
    const double margin = 2.0 * options.max_difference;
    for (std::size_t b = 0; b < second.size(); ++b) {
        const double target = second[b] + options.offset;
        auto it = std::lower_bound(first.begin(), first.end(), target - margin);
        for (; it != first.end() && *it <= target + margin; ++it) {
            const double diff = std::abs(*it - (second[b] + options.offset));
            if (diff < options.max_difference) candidates.push_back({diff, static_cast<std::size_t>(it - first.begin()), b});
        }
    }
    // Sorted lists: index order is stamp order, so (diff, a, b) sorts as Python's tuples do.
    std::sort(candidates.begin(), candidates.end(),
              [](const Candidate& x, const Candidate& y) { return std::tie(x.diff, x.a, x.b) < std::tie(y.diff, y.a, y.b); });
    std::vector<char> used_a(first.size(), 0), used_b(second.size(), 0);
    Association result;
    for (const Candidate& c : candidates) {
        if (used_a[c.a] || used_b[c.b]) continue;
        used_a[c.a] = used_b[c.b] = 1;
        result.matches.push_back({c.a, c.b});
        result.max_dt = std::max(result.max_dt, c.diff);
    }
    std::sort(result.matches.begin(), result.matches.end(),
              [](const Match& x, const Match& y) { return std::tie(x.first, x.second) < std::tie(y.first, y.second); });
    result.unmatched_first = first.size() - result.matches.size();
    result.unmatched_second = second.size() - result.matches.size();
    if (result.matches.empty()) {
        auto range = [](const std::vector<double>& v) {
            return v.empty() ? std::string("empty") : fmt::format("{:.6f} … {:.6f}", v.front(), v.back());
        };
        throw std::runtime_error(
            fmt::format("no time stamps matched within {} s (offset {} s): ground truth spans {} ({} poses), estimate spans {} "
                        "({} poses)",
                        options.max_difference, options.offset, range(first), first.size(), range(second), second.size()));
    }
    return result;
}

}  // namespace vobench::metrics
