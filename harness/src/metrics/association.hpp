// association.hpp — TUM's time-stamp association (associate.py / evaluate_ate.py, Sturm et al. 2012).
//
// Rule: every pair (a, b) with |a − (b + offset)| < max_difference is a candidate; candidates are
// sorted by (|a − (b + offset)|, a, b) — Python's tuple order — and accepted greedily, each stamp used
// at most once; the matches are returned sorted by a. The script enumerates all N·M pairs; here each
// b only looks at the a inside its window found by binary search, so the cost is
// O((N + M) log N + P log P) for P candidates (a handful per stamp), with the same result.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace vobench::metrics {

struct AssociationOptions {
    double max_difference = 0.02;  // seconds (strict: a pair must be closer than this)
    double offset = 0.0;           // seconds added to the second list's stamps
};

struct Match {
    std::size_t first;   // index into the first list (ground truth by convention)
    std::size_t second;  // index into the second list (estimate)
};

struct Association {
    std::vector<Match> matches;  // sorted by first stamp
    std::size_t unmatched_first = 0;
    std::size_t unmatched_second = 0;
    double max_dt = 0.0;  // the largest |a − (b + offset)| among the matches
};

// Both lists must be sorted ascending. Throws std::runtime_error when nothing matches, naming the two
// stamp ranges (the usual cause: wrong files, or stamps in other units or clocks).
Association associate(const std::vector<double>& first, const std::vector<double>& second, const AssociationOptions& options);

}  // namespace vobench::metrics
