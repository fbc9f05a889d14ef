// Rankings honest about noise: bootstrap intervals with a fixed seed, ties where they overlap,
// criteria summed or averaged as documented, unranked entries with failed cells.
#include "report/leaderboard.hpp"
#include "report/bootstrap.hpp"
#include "report/report_writer.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace vobench;

namespace {

RunRecord record(const std::string& algorithm, const std::string& sequence, uint64_t repeat, double ate, bool ok = true) {
    RunRecord r;
    r.cell.algorithm = r.cell.plugin = algorithm;
    r.cell.dataset = "d";
    r.cell.sequence = sequence;
    r.cell.repeat = repeat;
    r.cell.id = "0123456789abcdef";
    r.cell.gt_accuracy = {0.01, 1.0};
    r.ok = ok;
    r.reason = ok ? "" : "killed by signal 11 (SIGSEGV) at frame 2";
    r.run = {{"plugin", {{"version", "1"}}}, {"failed_at_frame", ok ? nlohmann::json(nullptr) : nlohmann::json(2)}};
    if (ok) {
        r.metrics["ate.rmse"] = ate;
        r.metrics["rpe.trans.rmse"] = ate / 2;
    }
    r.metrics["lost_frames"] = 1;
    return r;
}

}  // namespace

TEST_CASE("bootstrap interval of a mean: known cases", "[report]") {
    CHECK(bootstrap_mean_ci({2.5}) == std::pair<double, double>(2.5, 2.5));
    CHECK(bootstrap_mean_ci({1, 1, 1}) == std::pair<double, double>(1, 1));
    // 400 draws of N(10, 2): the 95 % interval of the mean is about ±1.96·2/√400 = ±0.196.
    std::mt19937_64 rng(3);
    std::normal_distribution<double> n(10, 2);
    std::vector<double> v(400);
    for (double& x : v) x = n(rng);
    double mean = 0;
    for (double x : v) mean += x;
    mean /= 400;
    const auto [lo, hi] = bootstrap_mean_ci(v);
    CHECK(lo < mean);
    CHECK(hi > mean);
    CHECK(hi - lo == Approx(2 * 0.196).epsilon(0.15));
    CHECK(bootstrap_mean_ci(v) == bootstrap_mean_ci(v));  // fixed seed
    CHECK_THROWS(bootstrap_mean_ci({}));
}

TEST_CASE("leaderboard: ranks, ties, criteria, failures", "[report]") {
    std::vector<RunRecord> records;
    // a and b overlap (noise), c is clearly worse, d has a failed cell.
    const double a[] = {0.010, 0.012, 0.011, 0.013}, b[] = {0.0115, 0.0125, 0.0105, 0.0135}, c[] = {0.05, 0.051, 0.052, 0.049};
    for (int k = 0; k < 4; ++k) {
        records.push_back(record("a", "s" + std::to_string(k % 2), k / 2, a[k]));
        records.push_back(record("b", "s" + std::to_string(k % 2), k / 2, b[k]));
        records.push_back(record("c", "s" + std::to_string(k % 2), k / 2, c[k]));
        records.push_back(record("d", "s" + std::to_string(k % 2), k / 2, 0.001, k != 3));
    }
    LeaderboardContext ctx;
    ctx.rank_by = "ate.rmse";
    ctx.criteria = {parse_criterion("ate.rmse <= 0.02"), parse_criterion("lost_frames == 4"), parse_criterion("failed_cells == 0")};
    const nlohmann::json lb = build_leaderboard(records, ctx);
    const auto& e = lb["entries"];
    REQUIRE(e.size() == 4);
    CHECK(e[0]["entry"] == "a");
    CHECK(e[0]["rank"] == 1);
    CHECK(e[1]["entry"] == "b");
    CHECK(e[1]["rank"] == 2);
    CHECK(e[2]["entry"] == "c");
    CHECK(e[3]["entry"] == "d");
    CHECK(e[3]["rank"].is_null());  // a failed cell: not ranked, though its mean is the lowest
    CHECK(e[3]["complete"] == false);
    CHECK(e[0]["tied_with"] == nlohmann::json::array({"b"}));
    CHECK(e[1]["tied_with"] == nlohmann::json::array({"a"}));
    CHECK(e[2]["tied_with"].empty());
    CHECK(e[0]["aggregate"]["ate.rmse"]["mean"] == Approx(0.0115));
    CHECK(e[0]["aggregate"]["lost_frames"]["sum"] == 4);
    // Criteria: a passes all three; c misses the accuracy; d misses failed_cells.
    CHECK(e[0]["criteria"][0]["passed"] == true);
    CHECK(e[0]["criteria"][1]["passed"] == true);
    CHECK(e[2]["criteria"][0]["passed"] == false);
    CHECK(e[3]["criteria"][2]["passed"] == false);
    CHECK(e[3]["criteria"][2]["value"] == 1);
    CHECK(lb["problems"][0]["passed_by"]["c"] == false);
    REQUIRE(lb["failures"].size() == 1);
    CHECK(lb["failures"][0]["failed_at_frame"] == 2);
    // Within the ground truth's own error (σ 1 cm): every ATE of a, not c's.
    CHECK(e[0]["cells"][0]["within_gt_error"] == nlohmann::json::array({"ate.rmse", "rpe.trans.rmse"}));
    CHECK(e[2]["cells"][0]["within_gt_error"] == nlohmann::json::array());
}

// The protocol sentence of summary.md and the page names the definitions actually used (issue #18 item 4).
TEST_CASE("the report's protocol text names the protocol used and its own reference", "[report]") {
    nlohmann::json tum = {{"name", "tum-scripts"},
                          {"max_difference_s", 0.02},
                          {"offset_s", 0.0},
                          {"ate", {{"alignment", "se3"}, {"align_first", 0}}},
                          {"rpe", {{"delta", 1.0}, {"delta_unit", "s"}}}};
    const std::string t = protocol_text(tum);
    CHECK(t.find("Protocol 'tum-scripts'") != std::string::npos);
    CHECK(t.find("Sturm et al. 2012") != std::string::npos);
    CHECK(t.find("evaluate_rpe.py") != std::string::npos);
    CHECK(t.find("RPE at Δ = 1 s") != std::string::npos);
    CHECK(t.find("Kraft") == std::string::npos);
    nlohmann::json paper = tum;
    paper["name"] = "paper";
    paper["rpe"] = {{"delta", 4.0}, {"delta_unit", "f"}};
    paper["ate"]["align_first"] = 50;
    const std::string q = protocol_text(paper);
    CHECK(q.find("(Kraft et al. 2016, eqs. 11–12)") != std::string::npos);
    CHECK(q.find("on the first 50 matched poses") != std::string::npos);
    CHECK(q.find("Sturm") == std::string::npos);
    // Hand-edited records: a field of the wrong type reads as its default, nothing throws.
    paper["rpe"]["delta"] = "four";
    paper["ate"]["alignment"] = 7;
    CHECK(protocol_text(paper).find("RPE at Δ = 4 f") != std::string::npos);
    CHECK(protocol_text(nlohmann::json::array()).empty());
}
