#include "metrics/trajectory_io.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>

using namespace vobench::metrics;
using Catch::Matchers::Contains;

namespace {

ReadResult parse(const std::string& text, TrajectoryFormat format = TrajectoryFormat::Tum, bool tum_scripts = false) {
    ReadOptions o;
    o.format = format;
    o.tum_scripts = tum_scripts;
    return parse_trajectory(text, "traj.txt", o);
}

bool has_warning(const ReadResult& r, const std::string& code) {
    for (const auto& w : r.warnings)
        if (w.find("[" + code + "]") != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("TUM: comments, spaces, tabs and commas", "[metrics][io]") {
    const ReadResult r = parse("# header\n1.0 1 2 3 0 0 0 1\n2.0\t1\t2\t3\t0\t0\t0\t1\n3.0,1,2,3,0,0,0,1\n\n");
    REQUIRE(r.poses.size() == 3);
    CHECK(r.poses[2].t == 3.0);
    CHECK(r.poses[1].p.y() == 2.0);
    CHECK(r.warnings.empty());
}

TEST_CASE("TUM: each malformed input is an error naming file and line", "[metrics][io]") {
    CHECK_THROWS_WITH(parse("1 2 3\n"), Contains("traj.txt:1: expected 8 values, found 3"));
    CHECK_THROWS_WITH(parse("# c\n1 0 0 0 0 0 0 1\n2 0 zero 0 0 0 0 1\n"), Contains("traj.txt:3: value 3 ('zero') is not a number"));
    CHECK_THROWS_WITH(parse("1 0 0 nan 0 0 0 1\n"), Contains("traj.txt:1: value 4 is not finite"));
    CHECK_THROWS_WITH(parse("1 0 0 0 0 0 0 0\n"), Contains("traj.txt:1: zero quaternion"));
    CHECK_THROWS_WITH(parse("# nothing\n"), Contains("traj.txt: no poses"));
}

TEST_CASE("TUM: named warnings for fixable problems", "[metrics][io]") {
    const ReadResult unsorted = parse("2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n");
    CHECK(has_warning(unsorted, "unsorted-stamps"));
    CHECK(unsorted.poses[0].t == 1.0);

    const ReadResult dup = parse("1 0 0 0 0 0 0 1\n1 5 0 0 0 0 0 1\n");
    CHECK(has_warning(dup, "duplicate-stamp"));
    REQUIRE(dup.poses.size() == 1);
    CHECK(dup.poses[0].p.x() == 5.0);  // the later line wins, as in the TUM scripts
    CHECK_THAT(dup.warnings[0], Contains("traj.txt:2:"));

    const ReadResult nonunit = parse("1 0 0 0 0 0 0 1.1\n");
    CHECK(has_warning(nonunit, "non-unit-quaternion"));
    CHECK(nonunit.poses[0].q.norm() == Approx(1.0));

    const ReadResult ns = parse("1305031229528748000 0 0 0 0 0 0 1\n1305031229628748000 0 0 0 0 0 0 1\n");
    CHECK(has_warning(ns, "stamps-in-nanoseconds"));
    CHECK(ns.poses[1].t == Approx(1305031229.628748));
}

TEST_CASE("TUM in tum-scripts mode skips NaN and zero-quaternion lines as evaluate_rpe.py", "[metrics][io]") {
    const ReadResult r = parse("1 0 0 0 0 0 0 1\n2 nan 0 0 0 0 0 1\n3 0 0 0 0 0 0 0\n4 0 0 0 0 0 0 1\n", TrajectoryFormat::Tum, true);
    REQUIRE(r.poses.size() == 2);
    CHECK(has_warning(r, "non-finite"));
    CHECK(has_warning(r, "zero-quaternion"));
}

TEST_CASE("KITTI rows become poses with the line index as stamp", "[metrics][io]") {
    const ReadResult r = parse("1 0 0 1.5 0 1 0 2.5 0 0 1 3.5\n0 -1 0 0 1 0 0 0 0 0 1 0\n", TrajectoryFormat::Kitti);
    REQUIRE(r.poses.size() == 2);
    CHECK(r.poses[1].t == 1.0);
    CHECK(r.poses[0].p == Eigen::Vector3d(1.5, 2.5, 3.5));
    CHECK(r.poses[1].q.angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()))) < 1e-12);
    CHECK_THROWS_WITH(parse("2 0 0 0 0 1 0 0 0 0 1 0\n", TrajectoryFormat::Kitti), Contains("traj.txt:1: the 3×3 part is not a rotation"));
}

TEST_CASE("EuRoC CSV: nanosecond stamps, w-first quaternion, extra columns", "[metrics][io]") {
    const std::string text =
        "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], v_x\n"
        "1403636579758555392, 4.688, -1.786, 0.783, 0.534, -0.153, -0.827, -0.082, 0.1\n";
    const ReadResult r = parse(text, TrajectoryFormat::Euroc);
    REQUIRE(r.poses.size() == 1);
    CHECK(r.poses[0].t == Approx(1403636579.758555392));
    CHECK(r.poses[0].q.w() == Approx(0.534 / std::sqrt(0.534 * 0.534 + 0.153 * 0.153 + 0.827 * 0.827 + 0.082 * 0.082)));
}

TEST_CASE("PUTK2 raw: Rodrigues vector, and eq. 10 with a camera-in-marker pose", "[metrics][io]") {
    const std::string text = "0;0;0;1.5707963267948966;1;2;3\n";
    const ReadResult marker = parse(text, TrajectoryFormat::Putk2Raw);
    REQUIRE(marker.poses.size() == 1);
    CHECK(marker.poses[0].p == Eigen::Vector3d(1, 2, 3));
    // The camera sits 1 m along the marker's x axis; the marker is turned 90° about z.
    ReadOptions o;
    o.format = TrajectoryFormat::Putk2Raw;
    Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
    C.translation() = Eigen::Vector3d(1, 0, 0);
    o.camera_in_marker = C;
    const ReadResult cam = parse_trajectory(text, "t", o);
    CHECK((cam.poses[0].p - Eigen::Vector3d(1, 3, 3)).norm() < 1e-12);
    CHECK_THROWS_WITH(parse("0;1;2\n", TrajectoryFormat::Putk2Raw), Contains("traj.txt:1: expected 7 values, found 3"));
    CHECK_THROWS_WITH(parse("1e20;0;0;0;0;0;0\n", TrajectoryFormat::Putk2Raw),
                      Contains("traj.txt:1: the frame id is not an integer in [0, 2^53]"));
}

TEST_CASE("writing is full precision and reads back bit for bit", "[metrics][io]") {
    vobench::test::TempDir dir;
    Trajectory t;
    StampedPose p;
    p.t = 1305031229.5287483;
    p.p = {0.1 + 0.2, 1.0 / 3.0, -2e-17};
    p.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.123456789, Eigen::Vector3d(1, 1, 0).normalized()));
    t.push_back(p);
    write_tum(dir.path() / "t.txt", t);
    const ReadResult r = read_trajectory(dir.path() / "t.txt");
    REQUIRE(r.poses.size() == 1);
    CHECK(r.poses[0].t == p.t);
    CHECK(r.poses[0].p == p.p);
    CHECK(r.poses[0].q.coeffs() == p.q.coeffs());
    CHECK_THROWS_WITH(read_trajectory(dir.path() / "missing.txt"), Contains("missing.txt: cannot open file"));
}
