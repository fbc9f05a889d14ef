// Properties any correct ATE/RPE must have, independent of reference numbers.
#include "metrics/evaluation.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace vobench::metrics;

namespace {

// A wandering 10 Hz trajectory.
Trajectory make_trajectory(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    Trajectory t;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int i = 0; i < n; ++i) {
        Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
        step.linear() = Eigen::AngleAxisd(0.02 * g(rng), Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized()).toRotationMatrix();
        step.translation() = Eigen::Vector3d(0.05 + 0.01 * g(rng), 0.01 * g(rng), 0.01 * g(rng));
        T = T * step;
        t.push_back(StampedPose::from_isometry(0.1 * i, T));
    }
    return t;
}

Trajectory perturb(const Trajectory& t, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, sigma);
    Trajectory out = t;
    for (auto& p : out) {
        p.p += Eigen::Vector3d(g(rng), g(rng), g(rng));
        p.q = (p.q * Eigen::Quaterniond(Eigen::AngleAxisd(g(rng), Eigen::Vector3d::UnitX()))).normalized();
    }
    return out;
}

Protocol paper() {
    Protocol p;
    p.rpe_delta = 4;
    return p;
}

}  // namespace

TEST_CASE("identical trajectories have zero error in both protocols", "[metrics][properties]") {
    const Trajectory gt = make_trajectory(200, 1);
    for (ProtocolName name : {ProtocolName::Paper, ProtocolName::TumScripts}) {
        Protocol p = paper();
        p.name = name;
        const Evaluation e = evaluate(gt, gt, p);
        CHECK(e.ate->stats.rmse < 1e-12);
        CHECK(e.rpe->trans.max < 1e-12);
        CHECK(e.rpe->rot_deg.max < 1e-5);  // arccos near 1 (tum-scripts) limits this one
    }
}

TEST_CASE("ATE and RPE do not change under a rigid change of the estimate's world frame", "[metrics][properties]") {
    const Trajectory gt = make_trajectory(300, 2);
    const Trajectory est = perturb(gt, 0.01, 3);
    Eigen::Isometry3d W = Eigen::Isometry3d::Identity();
    W.linear() = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.2, -1, 0.4).normalized()).toRotationMatrix();
    W.translation() = Eigen::Vector3d(5, -3, 12);
    Trajectory moved = est;
    for (auto& p : moved) p = StampedPose::from_isometry(p.t, W * p.isometry());
    for (ProtocolName name : {ProtocolName::Paper, ProtocolName::TumScripts}) {
        Protocol p = paper();
        p.name = name;
        const Evaluation a = evaluate(gt, est, p), b = evaluate(gt, moved, p);
        CHECK(a.ate->stats.rmse == Approx(b.ate->stats.rmse).epsilon(1e-9));
        CHECK(a.rpe->trans.rmse == Approx(b.rpe->trans.rmse).epsilon(1e-9));
        CHECK(a.rpe->rot_deg.rmse == Approx(b.rpe->rot_deg.rmse).epsilon(1e-6));
    }
}

TEST_CASE("a known drift gives the known RPE", "[metrics][properties]") {
    // P_i = D^i Q_i: a drift D applied in the world frame at every frame. Then
    // E_i = (Q_i⁻¹Q_j)⁻¹ Q_i⁻¹ D^Δ Q_j = Q_j⁻¹ D^Δ Q_j, so over Δ = 4 frames a pure translation d gives
    // ‖E‖ = 4‖d‖ with no rotation, and a pure rotation θ gives an angle of exactly 4θ.
    const Trajectory gt = make_trajectory(100, 4);
    auto drifted = [&](const Eigen::Isometry3d& D) {
        Trajectory est;
        Eigen::Isometry3d Dk = Eigen::Isometry3d::Identity();
        for (const StampedPose& q : gt) {
            est.push_back(StampedPose::from_isometry(q.t, Dk * q.isometry()));
            Dk = D * Dk;
        }
        return est;
    };
    Protocol p = paper();
    p.ate = false;

    Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
    shift.translation() = Eigen::Vector3d(0.001, -0.002, 0.0005);
    const Evaluation t = evaluate(gt, drifted(shift), p);
    CHECK(t.rpe->pairs.size() == gt.size() - 4);  // m = n − Δ
    CHECK(t.rpe->trans.min == Approx(4 * shift.translation().norm()).epsilon(1e-9));
    CHECK(t.rpe->trans.max == Approx(4 * shift.translation().norm()).epsilon(1e-9));
    CHECK(t.rpe->rot_deg.max < 1e-6);

    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.linear() = Eigen::AngleAxisd(0.1 * M_PI / 180.0, Eigen::Vector3d(1, 2, 2) / 3.0).toRotationMatrix();
    const Evaluation r = evaluate(gt, drifted(turn), p);
    CHECK(r.rpe->rot_deg.min == Approx(0.4).epsilon(1e-9));
    CHECK(r.rpe->rot_deg.max == Approx(0.4).epsilon(1e-9));
}

TEST_CASE("RPE delta units: seconds and metres pick the expected partners", "[metrics][properties]") {
    // Straight line at 1 m/s, 10 Hz: Δ = 0.4 s and Δ = 0.4 m both mean 4 frames.
    Trajectory gt;
    for (int i = 0; i < 50; ++i) {
        StampedPose p;
        p.t = 0.1 * i;
        p.p = {0.1 * i, 0, 0};
        gt.push_back(p);
    }
    Trajectory est = gt;
    for (auto& p : est) p.p.x() *= 1.1;  // 10% too long
    for (DeltaUnit unit : {DeltaUnit::Frames, DeltaUnit::Seconds, DeltaUnit::Metres}) {
        RpeOptions o;
        o.unit = unit;
        o.delta = unit == DeltaUnit::Frames ? 4.0 : 0.4 - 1e-9;
        const RpeResult r = compute_rpe_paper(gt, est, o);
        CHECK(r.trans.mean == Approx(0.04));
    }
}
