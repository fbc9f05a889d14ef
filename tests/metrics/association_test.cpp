#include "metrics/association.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

using namespace vobench::metrics;
using Catch::Matchers::Contains;

namespace {

// associate.py transcribed literally: all N·M pairs, sorted as Python tuples, greedy. The reference
// the fast version must equal.
std::vector<std::pair<std::size_t, std::size_t>> brute_force(const std::vector<double>& a, const std::vector<double>& b, double offset,
                                                             double max_difference) {
    std::vector<std::tuple<double, double, double, std::size_t, std::size_t>> potential;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j)
            if (std::abs(a[i] - (b[j] + offset)) < max_difference)
                potential.emplace_back(std::abs(a[i] - (b[j] + offset)), a[i], b[j], i, j);
    std::sort(potential.begin(), potential.end());
    std::vector<char> ua(a.size()), ub(b.size());
    std::vector<std::pair<std::size_t, std::size_t>> matches;
    for (const auto& [d, va, vb, i, j] : potential) {
        if (ua[i] || ub[j]) continue;
        ua[i] = ub[j] = 1;
        matches.emplace_back(i, j);
    }
    std::sort(matches.begin(), matches.end());
    return matches;
}

}  // namespace

TEST_CASE("association accepts the closest pairs first, one to one", "[metrics][association]") {
    const std::vector<double> gt = {0.00, 0.01, 0.02, 0.03, 0.10};
    const std::vector<double> est = {0.012, 0.029, 0.5};
    const Association r = associate(gt, est, {});
    REQUIRE(r.matches.size() == 2);
    CHECK(r.matches[0].first == 1);  // 0.01 ↔ 0.012
    CHECK(r.matches[0].second == 0);
    CHECK(r.matches[1].first == 3);  // 0.03 ↔ 0.029
    CHECK(r.unmatched_first == 3);
    CHECK(r.unmatched_second == 1);
    CHECK(r.max_dt == Approx(0.002));
}

TEST_CASE("association is strict at max_difference and applies the offset", "[metrics][association]") {
    CHECK_THROWS(associate({1.0}, {1.5}, {0.5, 0.0}));  // |diff| == max_difference: not a pair
    const Association r = associate({1.0}, {0.0}, {0.02, 1.0});
    CHECK(r.matches.size() == 1);
}

TEST_CASE("association equals the literal O(N·M) script on random stamps with ties", "[metrics][association]") {
    std::mt19937 rng(1234);
    for (int trial = 0; trial < 50; ++trial) {
        std::vector<double> a, b;
        double t = 0;
        for (int i = 0; i < 200; ++i) a.push_back(t += 0.01 * (1 + rng() % 3));  // 100 Hz-ish, many ties
        t = 0.005 * (rng() % 4);
        for (int i = 0; i < 80; ++i) b.push_back(t += 0.03 * (1 + rng() % 2));
        const double offset = 0.001 * (static_cast<int>(rng() % 20) - 10);
        const auto expected = brute_force(a, b, offset, 0.02);
        if (expected.empty()) continue;
        const Association got = associate(a, b, {0.02, offset});
        REQUIRE(got.matches.size() == expected.size());
        for (std::size_t k = 0; k < expected.size(); ++k) {
            CHECK(got.matches[k].first == expected[k].first);
            CHECK(got.matches[k].second == expected[k].second);
        }
    }
}

TEST_CASE("zero matches is an error that states both stamp ranges", "[metrics][association]") {
    CHECK_THROWS_WITH(associate({1.0, 2.0}, {1e9, 1e9 + 1}, {}), Contains("ground truth spans 1.000000 … 2.000000 (2 poses)") &&
                                                                     Contains("estimate spans 1000000000.000000 … 1000000001.000000"));
}
