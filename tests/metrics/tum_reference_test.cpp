// The published outputs of the TUM benchmark scripts on real trajectories
// (../shared/data/real/trajectories; numbers from evaluate_ate.py / evaluate_rpe.py, see SOURCES.md).
#include "metrics/evaluation.hpp"
#include "metrics/trajectory_io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

using namespace vobench::metrics;

namespace {

Trajectory load(const std::filesystem::path& p) {
    ReadOptions o;
    o.tum_scripts = true;
    return read_trajectory(p, o).poses;
}

// Printed with %f by the scripts: six decimals.
void check6(double value, double published) { CHECK(value == Approx(published).margin(5e-7)); }

}  // namespace

TEST_CASE("evaluate_ate.py on fr2/desk ORB-SLAM: 2223 pairs, rmse 0.008144", "[metrics][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "real/trajectories");
    Protocol p;
    p.name = ProtocolName::TumScripts;
    p.rpe = false;
    const Evaluation e = evaluate(load(dir / "freiburg2_desk-groundtruth.txt"), load(dir / "freiburg2_desk-ORB.txt"), p);
    const ErrorStats& s = e.ate->stats;
    CHECK(s.count == 2223);
    check6(s.rmse, 0.008144);
    check6(s.mean, 0.007514);
    check6(s.median, 0.007432);
    check6(s.std, 0.003140);
    check6(s.min, 0.000332);
    check6(s.max, 0.024329);
}

TEST_CASE("evaluate_ate.py and evaluate_rpe.py on fr1/xyz RGBDSLAM", "[metrics][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "real/trajectories");
    const Trajectory gt = load(dir / "freiburg1_xyz-groundtruth.txt");
    const Trajectory est = load(dir / "freiburg1_xyz-rgbdslam.txt");
    Protocol p;
    p.name = ProtocolName::TumScripts;
    p.rpe_delta = 1;
    p.rpe_unit = DeltaUnit::Frames;
    const Evaluation frames = evaluate(gt, est, p);
    CHECK(frames.ate->stats.count == 786);
    check6(frames.ate->stats.rmse, 0.013473);
    check6(frames.rpe->trans.rmse, 0.005763);
    check6(frames.rpe->rot_deg.rmse, 0.352969);

    p.ate = false;
    p.rpe_unit = DeltaUnit::Seconds;
    const Evaluation seconds = evaluate(gt, est, p);
    check6(seconds.rpe->trans.rmse, 0.021217);
    check6(seconds.rpe->rot_deg.rmse, 0.934480);
}

TEST_CASE("paper and tum-scripts RPE differ only by their documented pair rules", "[metrics][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "real/trajectories");
    const Trajectory gt = load(dir / "freiburg1_xyz-groundtruth.txt");
    const Trajectory est = load(dir / "freiburg1_xyz-rgbdslam.txt");
    RpeOptions o;
    o.delta = 1;
    const RpeResult paper = compute_rpe_paper(gt, est, o);
    const RpeResult scripts = compute_rpe_tum_scripts(gt, est, o);
    // The scripts drop every pair ending on the last pose and gt beyond 2× the median interval; the
    // paper protocol keeps all n − Δ associated pairs (786 − 1).
    CHECK(paper.pairs.size() == 785);
    CHECK(scripts.pairs.size() == 783);
    CHECK(paper.trans.rmse == Approx(scripts.trans.rmse).epsilon(0.01));
}
