// Ground-truth quality (Ceriani et al. 2009): comparison at validation poses with known answers, and
// fusion of two noisy streams with known truth.
#include "groundtruth/gt_compare.hpp"
#include "groundtruth/gt_fusion.hpp"
#include "metrics/statistics.hpp"
#include "metrics/trajectory_io.hpp"
#include "test_support.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

using namespace vobench;

namespace {

// A smooth path: a 2 m circle at 0.3 rad/s with a small height and roll wobble, heading along it.
metrics::StampedPose truth(double t) {
    metrics::StampedPose p;
    p.t = t;
    p.p = {2 * std::cos(0.3 * t), 2 * std::sin(0.3 * t), 0.1 * std::sin(t)};
    p.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * t + M_PI / 2, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.05 * std::sin(t), Eigen::Vector3d::UnitX()));
    return p;
}

metrics::StampedPose noisy(const metrics::StampedPose& p, double sigma_pos, double sigma_rot_deg, std::mt19937_64& rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    metrics::StampedPose q = p;
    q.p += sigma_pos * Eigen::Vector3d(n(rng), n(rng), n(rng));
    const Eigen::Vector3d w = sigma_rot_deg * M_PI / 180.0 * Eigen::Vector3d(n(rng), n(rng), n(rng));
    q.q = (p.q * Eigen::Quaterniond(Eigen::AngleAxisd(w.norm(), w.normalized()))).normalized();
    return q;
}

// A stream every `step` s over [0, 20] s, with a gap [gap0, gap1).
metrics::Trajectory stream(double step, double gap0, double gap1, double sp, double sr, uint64_t seed) {
    std::mt19937_64 rng(seed);
    metrics::Trajectory t;
    for (double s = 0; s <= 20.0 + 1e-9; s += step)
        if (s < gap0 || s >= gap1) t.push_back(noisy(truth(s), sp, sr, rng));
    return t;
}

double position_rmse(const metrics::Trajectory& t) {
    double sse = 0;
    for (const auto& p : t) sse += (p.p - truth(p.t).p).squaredNorm();
    return std::sqrt(sse / static_cast<double>(t.size()));
}

double rotation_rmse_deg(const metrics::Trajectory& t) {
    double sse = 0;
    for (const auto& p : t) {
        const double a = Eigen::AngleAxisd(truth(p.t).q.conjugate() * p.q).angle() * 180 / M_PI;
        sse += a * a;
    }
    return std::sqrt(sse / static_cast<double>(t.size()));
}

}  // namespace

TEST_CASE("gt compare: known offsets at validation poses, counted as Rawseeds does", "[gt]") {
    metrics::Trajectory gt, validation;
    for (int k = 0; k <= 210; ++k) {
        metrics::StampedPose p = truth(0.1 * k);
        p.p.x() += 0.03;  // the ground truth is 3 cm off in x everywhere
        p.q = (p.q * Eigen::Quaterniond(Eigen::AngleAxisd(2.0 * M_PI / 180, Eigen::Vector3d::UnitY()))).normalized();  // and 2° off
        if (k <= 120 || k > 140) gt.push_back(p);  // a gap (12.0, 14.0] s
    }
    for (int k = 0; k < 26; ++k) validation.push_back(truth(0.8 * k + 0.005));  // 26 poses, 5 ms after a gt stamp
    gt::CompareOptions o;
    const gt::CompareResult r = gt::compare_ground_truth(gt, validation, o);
    CHECK(r.validation_poses == 26);
    CHECK(r.localised == 24);  // 12.8 s and 13.6 s fall in the gap (0.8·16, 0.8·17)
    // Truth at +5 ms differs from truth at the gt stamp by the motion over 5 ms (0.6 m/s · 5 ms = 3 mm).
    CHECK(r.position_m.mean == Approx(0.03).margin(0.004));
    CHECK(r.position_m.max < 0.034);
    CHECK(r.rotation_deg.mean == Approx(2.0).margin(0.1));
    CHECK(gt::compare_table(r).find("| 24/26 |") != std::string::npos);

    // By id: equal stamps only.
    metrics::Trajectory exact;
    for (int k = 0; k < 26; ++k) exact.push_back(truth(0.8 * k));
    o.by = gt::MatchBy::Id;
    const gt::CompareResult by_id = gt::compare_ground_truth(gt, exact, o);
    CHECK(by_id.localised == 24);
    CHECK(by_id.position_m.mean == Approx(0.03).margin(1e-12));
    CHECK(by_id.position_m.std == Approx(0.0).margin(1e-12));
    CHECK(by_id.rotation_deg.max == Approx(2.0).margin(1e-9));
    // With --align the constant offset disappears.
    o.align = true;
    CHECK(gt::compare_ground_truth(gt, exact, o).position_m.max < 1e-9);
}

TEST_CASE("gt fuse: the fused stream beats both inputs against the known truth", "[gt]") {
    gt::PoseStream a, b;
    a.poses = stream(0.10, 4.0, 6.0, 0.02, 1.0, 11);  // camera-network-like: 10 Hz, 2 cm, 1°, a 2 s gap
    a.sigma_pos_m = 0.02;
    a.sigma_rot_deg = 1.0;
    b.poses = stream(0.15, 12.0, 14.0, 0.05, 2.0, 12);  // laser-like: 6.7 Hz, 5 cm, 2°, another gap
    b.sigma_pos_m = 0.05;
    b.sigma_rot_deg = 2.0;
    const auto fused = gt::fuse_ground_truth(a, b, {});
    metrics::Trajectory f;
    for (const auto& p : fused) f.push_back(p.pose);
    const double ra = position_rmse(a.poses), rb = position_rmse(b.poses), rf = position_rmse(f);
    INFO("position RMSE: A " << ra << ", B " << rb << ", fused " << rf);
    CHECK(rf < ra);
    CHECK(rf < rb);
    CHECK(rf < 0.7 * ra);
    const double qa = rotation_rmse_deg(a.poses), qb = rotation_rmse_deg(b.poses), qf = rotation_rmse_deg(f);
    INFO("rotation RMSE: A " << qa << "°, B " << qb << "°, fused " << qf << "°");
    CHECK(qf < qa);
    CHECK(qf < qb);
    // The gaps are bridged: a fused pose at every stamp of either stream.
    std::size_t covered = 0;  // every stamp of either stream has its fused pose
    for (const auto* s : {&a.poses, &b.poses})
        for (const auto& p : *s)
            covered += std::any_of(fused.begin(), fused.end(), [&](const gt::FusedPose& f) { return std::abs(f.pose.t - p.t) < 1e-6; });
    CHECK(covered == a.poses.size() + b.poses.size());
    // Covariances: symmetric, positive, and larger inside A's gap (only B there) than where both speak.
    auto sigma_at = [&](double t) {
        for (const auto& p : fused)
            if (std::abs(p.pose.t - t) < 0.051) return std::sqrt(p.covariance(0, 0));
        return -1.0;
    };
    for (const auto& p : fused) {
        CHECK((p.covariance - p.covariance.transpose()).norm() < 1e-12);
        CHECK(p.covariance.diagonal().minCoeff() > 0);
    }
    CHECK(sigma_at(5.0) > sigma_at(9.0));
    CHECK(sigma_at(9.0) < 0.02);  // better than A's own σ where both streams speak

    // Odometry as the motion input helps further inside the gaps.
    gt::PoseStream odo;
    odo.poses = stream(0.05, 100, 100, 0.0, 0.0, 13);  // exact relative motion
    odo.sigma_pos_m = 0.02;
    odo.sigma_rot_deg = 0.5;
    gt::FusionOptions with_odo;
    with_odo.odometry = odo;
    metrics::Trajectory g;
    for (const auto& p : gt::fuse_ground_truth(a, b, with_odo)) g.push_back(p.pose);
    INFO("with odometry: " << position_rmse(g));
    CHECK(position_rmse(g) < rf);
}

TEST_CASE("gt fuse refuses bad input", "[gt]") {
    gt::PoseStream a, b;
    a.poses = stream(0.1, 0, 0, 0.01, 1, 1);
    CHECK_THROWS_WITH(gt::fuse_ground_truth(a, b, {}), Catch::Contains("both streams need poses"));
    b.poses = a.poses;
    b.sigma_pos_m = 0;
    CHECK_THROWS_WITH(gt::fuse_ground_truth(a, b, {}), Catch::Contains("sigmas must be positive"));
}

TEST_CASE("vobench gt compare and gt fuse on files", "[gt]") {
    test::TempDir dir;
    metrics::Trajectory gt, val;
    for (int k = 0; k < 100; ++k) {
        metrics::StampedPose p = truth(0.1 * k);
        p.p.z() += 0.05;
        gt.push_back(p);
    }
    for (int k = 0; k < 10; ++k) val.push_back(truth(1.0 * k));
    val.push_back(truth(50.0));  // outside the ground truth: not localised
    metrics::write_tum(dir.path() / "gt.txt", gt);
    metrics::write_tum(dir.path() / "val.txt", val);
    std::string out;
    REQUIRE(test::run_command(test::cli().string() + " gt compare --gt " + (dir.path() / "gt.txt").string() + " --validation " +
                                  (dir.path() / "val.txt").string() + " --json",
                              out) == 0);
    const auto j = nlohmann::json::parse(out);
    CHECK(j["localised"] == 10);
    CHECK(j["validation_poses"] == 11);
    CHECK(j["position_m"]["mean"].get<double>() == Approx(0.05).margin(1e-9));
    REQUIRE(test::run_command(test::cli().string() + " gt compare --gt " + (dir.path() / "gt.txt").string() + " --validation " +
                                  (dir.path() / "val.txt").string(),
                              out) == 0);
    CHECK_THAT(out, Catch::Contains("| 10/11 | 0.0500 |"));

    metrics::write_tum(dir.path() / "a.txt", stream(0.1, 4, 6, 0.02, 1, 21));
    metrics::write_tum(dir.path() / "b.txt", stream(0.15, 12, 14, 0.05, 2, 22));
    const auto fused = dir.path() / "fused.txt";
    REQUIRE(test::run_command(test::cli().string() + " gt fuse " + (dir.path() / "a.txt").string() + " " + (dir.path() / "b.txt").string() +
                                  " --sigma-a 0.02,1 --sigma-b 0.05,2 --out " + fused.string() + " 2>&1",
                              out) == 0);
    const metrics::Trajectory f = metrics::read_trajectory(fused).poses;
    CHECK(position_rmse(f) < position_rmse(metrics::read_trajectory(dir.path() / "a.txt").poses));
    std::ifstream cov(fused.string() + ".cov");
    std::string line;
    std::getline(cov, line);  // header
    std::getline(cov, line);
    std::istringstream fields(line);
    int count = 0;
    for (double v; fields >> v;) ++count;
    CHECK(count == 37);  // stamp + 6×6
    CHECK(test::run_command(test::cli().string() + " gt fuse " + (dir.path() / "a.txt").string() + " " + (dir.path() / "b.txt").string() +
                                " --sigma-a x --sigma-b 0.05 --out " + fused.string() + " 2>&1",
                            out) != 0);
    CHECK_THAT(out, Catch::Contains("--sigma-a"));
}
