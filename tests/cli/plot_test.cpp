// `vobench plot` end to end: three estimates in three formats (TUM, EuRoC, KITTI), each the reference
// moved by a known rigid motion, drawn against it in every mode; the drawn (aligned) positions must be
// the reference's, the figure written in all three formats, bad input refused by name.
#include "metrics/pose.hpp"
#include "test_support.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

using namespace vobench;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// A helix with turning orientation at 10 Hz, stamps k / 10 s.
metrics::Trajectory helix() {
    metrics::Trajectory t;
    for (int k = 0; k < 60; ++k) {
        const double a = 0.1 * k;
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.3 * std::sin(a), Eigen::Vector3d::UnitX()))
                         .toRotationMatrix();
        T.translation() = Eigen::Vector3d(std::cos(a), std::sin(a), 0.05 * k);
        t.push_back(metrics::StampedPose::from_isometry(0.1 * k, T));
    }
    return t;
}

Eigen::Isometry3d motion(double angle, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
    Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
    M.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
    M.translation() = t;
    return M;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The data file's blocks: rows of numbers (t x y z ...), '?' as NaN.
std::vector<std::vector<std::vector<double>>> blocks(const std::string& text) {
    std::vector<std::vector<std::vector<double>>> out(1);
    std::istringstream in(text);
    int blank = 0;
    for (std::string line; std::getline(in, line);) {
        if (line.empty()) {
            if (++blank == 2 && !out.back().empty()) out.emplace_back();
            continue;
        }
        blank = 0;
        if (line[0] == '#') continue;
        std::istringstream row(line);
        std::vector<double> values;
        for (std::string cell; row >> cell;) values.push_back(cell == "?" ? NAN : std::stod(cell));
        out.back().push_back(values);
    }
    if (out.back().empty()) out.pop_back();
    return out;
}

}  // namespace

TEST_CASE("vobench plot draws TUM, EuRoC and KITTI estimates aligned to a reference", "[cli][plot]") {
    test::TempDir dir;
    const metrics::Trajectory gt = helix();
    const Eigen::Isometry3d m1 = motion(0.7, {0, 0, 1}, {2, -1, 0.5}), m2 = motion(-1.1, {1, 2, 3}, {0.3, 0.2, -4}),
                            m3 = motion(2.0, {0, 1, 0}, {-1, 5, 2});
    std::string ref, tum, euroc = "#timestamp [ns],p_x,p_y,p_z,q_w,q_x,q_y,q_z\n", kitti;
    for (const metrics::StampedPose& p : gt) {
        auto row = [&](const Eigen::Isometry3d& M) { return metrics::StampedPose::from_isometry(p.t, M * p.isometry()); };
        const metrics::StampedPose a = row(Eigen::Isometry3d::Identity()), b = row(m1), c = row(m2), d = row(m3);
        ref += fmt::format("{:.9f} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", a.t, a.p.x(), a.p.y(), a.p.z(), a.q.x(),
                           a.q.y(), a.q.z(), a.q.w());
        tum += fmt::format("{:.9f} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}\n", b.t, b.p.x(), b.p.y(), b.p.z(), b.q.x(),
                           b.q.y(), b.q.z(), b.q.w());
        euroc += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", std::llround(c.t * 1e9), c.p.x(), c.p.y(),
                             c.p.z(), c.q.w(), c.q.x(), c.q.y(), c.q.z());
        const Eigen::Matrix4d K = d.isometry().matrix();
        for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 4; ++col) kitti += fmt::format("{:.17g}{}", K(r, col), r == 2 && col == 3 ? "\n" : " ");
    }
    write(dir.path() / "gt.txt", ref);
    write(dir.path() / "a.txt", tum);
    write(dir.path() / "b.csv", euroc);
    write(dir.path() / "c.kitti", kitti);
    const std::string base = test::cli().string() + " -q plot --ref " + (dir.path() / "gt.txt").string() + " " +
                             (dir.path() / "a.txt").string() + " " + (dir.path() / "b.csv").string() + " " +
                             (dir.path() / "c.kitti").string() +
                             " --format tum --format euroc --format kitti --index-rate 10 --label tum --label euroc --label kitti";
    for (const std::string mode : {"xy", "xz", "xyz", "rpy", "speed"}) {
        INFO(mode);
        const fs::path out = dir.path() / ("fig_" + mode + ".pdf");
        std::string text;
        REQUIRE(test::run_command(base + " --mode " + mode + " --out " + out.string(), text) == 0);
        CHECK_THAT(text, Contains("tum: 60 poses, 60 matched") && Contains("euroc: 60 poses, 60 matched") &&
                             Contains("kitti: 60 poses, 60 matched"));
        for (const char* ext : {".png", ".svg", ".pdf", ".dat", ".gp"})
            CHECK(fs::file_size(out.parent_path() / (out.stem().string() + ext)) > 100);
        // Every estimate drawn where the reference is: positions and orientations (roll, pitch, yaw).
        const auto b = blocks(read(out.parent_path() / (out.stem().string() + ".dat")));
        REQUIRE(b.size() == 4);
        for (std::size_t k = 1; k < 4; ++k) {
            REQUIRE(b[k].size() == 60);
            for (std::size_t i = 0; i < 60; ++i)
                for (int c = 0; c < 7; ++c) REQUIRE(std::abs(b[k][i][c] - b[0][i][c]) < 1e-6);
        }
    }

    // The interactive variant: one page, its data island holding the four tracks, each estimate
    // (positions and orientations) where the reference is, to display precision.
    const fs::path page = dir.path() / "fig.html";
    std::string text;
    REQUIRE(test::run_command(base + " --out " + page.string(), text) == 0);
    CHECK_THAT(text, Contains("Page: " + page.string()));
    const std::string html = read(page);
    const std::string open = "<script type=\"application/json\" id=\"vobench-data\">";
    const std::size_t from = html.find(open);
    REQUIRE(from != std::string::npos);
    const auto data = nlohmann::json::parse(html.substr(from + open.size(), html.find("</script>", from) - from - open.size()));
    CHECK(data["kind"] == "plot");
    const auto& tracks = data["views"][0]["tracks"];
    REQUIRE(tracks.size() == 4);
    CHECK(tracks[0]["role"] == "reference");
    for (std::size_t k = 1; k < 4; ++k) {
        REQUIRE(tracks[k]["p"].size() == 180);
        for (std::size_t i = 0; i < 180; ++i) REQUIRE(std::abs(tracks[k]["p"][i].get<double>() - tracks[0]["p"][i].get<double>()) < 2e-5);
        for (std::size_t i = 0; i < 240; i += 4) {
            const Eigen::Quaterniond a(tracks[k]["q"][i], tracks[k]["q"][i + 1], tracks[k]["q"][i + 2], tracks[k]["q"][i + 3]);
            const Eigen::Quaterniond r(tracks[0]["q"][i], tracks[0]["q"][i + 1], tracks[0]["q"][i + 2], tracks[0]["q"][i + 3]);
            REQUIRE(a.angularDistance(r) < 1e-4);
        }
    }
}

TEST_CASE("vobench plot refuses a figure name it cannot quote and an estimate it cannot align, by name", "[cli][plot]") {
    test::TempDir dir;
    write(dir.path() / "gt.txt", "0 0 0 0 0 0 0 1\n0.1 1 0 0 0 0 0 1\n0.2 1 1 0 0 0 0 1\n0.3 0 1 1 0 0 0 1\n");
    write(dir.path() / "far.txt", "50 0 0 0 0 0 0 1\n50.1 1 0 0 0 0 0 1\n50.2 1 1 0 0 0 0 1\n");
    std::string text;
    const std::string cli = test::cli().string() + " -q plot --ref " + (dir.path() / "gt.txt").string() + " ";
    CHECK(test::run_command(cli + (dir.path() / "gt.txt").string() + " --out \"" + (dir.path() / "bad name;x.png").string() + "\" 2>&1",
                            text) != 0);
    CHECK_THAT(text, Contains("plain file name"));
    CHECK(test::run_command(cli + (dir.path() / "gt.txt").string() + " --out " + (dir.path() / "fig.jpg").string() + " 2>&1", text) != 0);
    CHECK_THAT(text, Contains(".png, .svg, .pdf or .html"));
    CHECK(test::run_command(cli + (dir.path() / "far.txt").string() + " --out " + (dir.path() / "fig.png").string() + " 2>&1", text) != 0);
    CHECK_THAT(text, Contains("far.txt: cannot be aligned to gt.txt"));
    CHECK_FALSE(fs::exists(dir.path() / "fig.png"));
}
