#include "metrics/alignment.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <random>

using namespace vobench::metrics;

namespace {

Eigen::Matrix3Xd random_points(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    Eigen::Matrix3Xd m(3, n);
    for (int i = 0; i < n; ++i) m.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
    return m;
}

}  // namespace

TEST_CASE("se3 and sim3 recover a known transform exactly", "[metrics][alignment]") {
    const Eigen::Matrix3Xd model = random_points(50, 1);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::Vector3d t(0.3, -1.2, 2.0);
    const Eigen::Matrix3Xd data = (R * model).colwise() + t;
    const Alignment a = align(model, data, AlignmentMethod::Se3);
    CHECK((a.R - R).norm() < 1e-12);
    CHECK((a.t - t).norm() < 1e-12);
    CHECK(a.scale == 1.0);

    const Eigen::Matrix3Xd scaled = ((2.5 * R) * model).colwise() + t;
    const Alignment s = align(model, scaled, AlignmentMethod::Sim3);
    CHECK(s.scale == Approx(2.5).epsilon(1e-12));
    CHECK((s.R - R).norm() < 1e-12);
    CHECK((s.t - t).norm() < 1e-11);
}

TEST_CASE("se3 never returns a reflection", "[metrics][alignment]") {
    const Eigen::Matrix3Xd model = random_points(20, 2);
    Eigen::Matrix3Xd mirrored = model;
    mirrored.row(2) *= -1.0;
    const Alignment a = align(model, mirrored, AlignmentMethod::Se3);
    CHECK(a.R.determinant() == Approx(1.0));
}

TEST_CASE("posyaw recovers a rotation about z and a translation", "[metrics][alignment]") {
    const Eigen::Matrix3Xd model = random_points(30, 3);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(-2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d t(1, 2, 3);
    const Alignment a = align(model, (R * model).colwise() + t, AlignmentMethod::PosYaw);
    CHECK((a.R - R).norm() < 1e-12);
    CHECK((a.t - t).norm() < 1e-12);
}

TEST_CASE("first-N alignment uses only the first N pairs", "[metrics][alignment]") {
    const Eigen::Matrix3Xd model = random_points(10, 4);
    Eigen::Matrix3Xd data = model;
    data.rightCols(5).array() += 10.0;  // the tail drifted away
    const Alignment a = align(model, data, AlignmentMethod::Se3, 5);
    CHECK((a.R - Eigen::Matrix3d::Identity()).norm() < 1e-12);
    CHECK(a.t.norm() < 1e-12);
    CHECK_THROWS_WITH(align(model, data, AlignmentMethod::Se3, 2), Catch::Matchers::Contains("at least 3 matched poses"));
    CHECK(align(model, data, AlignmentMethod::None).t.norm() == 0.0);
    CHECK_THROWS(parse_alignment("se4"));
}
