// The interactive page's pieces: timing.csv read back as track/ writes it, the display decimation,
// a cell's view (the frusta's orientations are the aligned estimate's), and the data island, which no
// string can break out of.
#include "metrics/evaluation.hpp"
#include "record/run_record.hpp"
#include "record/timing_csv.hpp"
#include "report/interactive_page.hpp"
#include "report/report_assets.hpp"
#include "report/trajectory_view.hpp"
#include "test_support.hpp"
#include "track/track.hpp"
#include "util/files.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace vobench;
using vobench::test::TempDir;
namespace fs = std::filesystem;

namespace {

TrackResult track_result(std::size_t n, bool with_dropped) {
    TrackResult r;
    for (std::size_t k = 0; k < n; ++k) {
        FrameRecord f;
        f.index = k;
        f.stamp = 100.0 + 0.05 * static_cast<double>(k);
        f.process_ns = 2'000'000 + 1000 * static_cast<int64_t>(k);
        f.read_ns = 500'000;
        f.dropped = with_dropped && k == 3;
        f.tracking = k == 5 ? VOBENCH_TRACKING_LOST : VOBENCH_TRACKING_OK;
        if (!f.dropped) f.stages = {{"detect", 1'500'000}, {"track", 500'000 + 1000 * static_cast<int64_t>(k)}};
        if (!f.dropped && k % 2 == 0) f.counters = {{"inliers", 100.0 + static_cast<double>(k)}};
        r.frames.push_back(f);
        metrics::StampedPose p;
        p.t = f.stamp;
        p.p = {0.1 * static_cast<double>(k), 0.02 * std::sin(static_cast<double>(k)), 0.0};
        p.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * static_cast<double>(k), Eigen::Vector3d::UnitY()));
        r.estimate.push_back(p);
    }
    return r;
}

}  // namespace

TEST_CASE("timing.csv reads back what the track writes, a dropped frame as NaN", "[report][interactive]") {
    TempDir dir;
    write_track_outputs(track_result(12, true), dir.path());
    const TimingTable t = read_timing_csv(dir.path() / "timing.csv");
    REQUIRE(t.stamps.size() == 12);
    CHECK(t.stamps[4] == Approx(100.2).margin(1e-12));
    CHECK(t.process_ms[4] == Approx(2.004).margin(1e-12));
    CHECK(std::isnan(t.process_ms[3]));
    CHECK(t.read_ms[3] == Approx(0.5));
    CHECK(t.status[3] == "dropped");
    CHECK(t.status[5] == "lost");
    REQUIRE(t.stages.size() == 2);
    CHECK(t.stages[0].name == "detect");
    CHECK(t.stages[1].name == "track");
    CHECK(t.stages[1].ms[7] == Approx(0.507).margin(1e-12));
    CHECK(std::isnan(t.stages[0].ms[3]));
}

TEST_CASE("timing.csv that is not what a run writes is refused naming file:line and the column", "[report][interactive]") {
    TempDir dir;
    const fs::path f = dir.path() / "timing.csv";
    const auto refused = [&](const std::string& text, const std::string& message) {
        write_file_atomic(f, text);
        CHECK_THROWS_WITH(read_timing_csv(f), Catch::Contains(message));
    };
    refused("", "empty");
    refused("a,b,c\n", "timing.csv:1: not a timing.csv header");
    refused("index,stamp,process_ms,read_ms,status\n0,1,inf,0,ok\n", "timing.csv:2 process_ms: 'inf' is not a finite number");
    refused("index,stamp,process_ms,read_ms,status\n0,1,2,0,ok,5\n", "timing.csv:2: 6 columns, the header has 5");
    refused("index,stamp,process_ms,read_ms,status\n0,1,2,0,maybe\n", "status 'maybe' is none of");
    refused("index,stamp,process_ms,read_ms,status,stage_x_ms\n0,1,2,0,ok,-3\n", "stage x has a negative time");
    refused("index,stamp,process_ms,read_ms,status\n0,1,2x,0,ok\n", "'2x' is not a finite number");
    write_file_atomic(f, "index,stamp,process_ms,read_ms,status\n0,1,2,0,ok\n");
    CHECK_THROWS_WITH(read_timing_csv(f, 10), Catch::Contains("more than the 10 a timing file may have"));
    CHECK_THROWS_WITH(read_timing_csv(dir.path() / "none.csv"), Catch::Contains("none.csv: cannot read"));
}

TEST_CASE("display decimation keeps the first and last pose and at most the limit", "[report][interactive]") {
    CHECK(display_indices(0, 10).empty());
    CHECK(display_indices(1, 10) == std::vector<std::size_t>{0});
    CHECK(display_indices(10, 10).size() == 10);
    for (std::size_t n : {11u, 1499u, 1501u, 10000u, 123457u}) {
        const auto shown = display_indices(n, 1500);
        INFO(n);
        CHECK(shown.front() == 0);
        CHECK(shown.back() == n - 1);
        CHECK(shown.size() <= std::max<std::size_t>(n <= 1500 ? n : 1500, 2));
        for (std::size_t k = 1; k + 1 < shown.size(); ++k) CHECK(shown[k] - shown[k - 1] == shown[1] - shown[0]);
    }
}

TEST_CASE("a cell's view: the estimate as ATE aligned it, its orientations rotated by the alignment", "[report][interactive]") {
    TempDir dir;
    const TrackResult tr = track_result(40, false);
    write_track_outputs(tr, dir.path());
    // Ground truth: the estimate turned by 30° about z and moved; SE(3) alignment recovers that map.
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitZ()));
    metrics::Trajectory gt;
    for (const auto& p : tr.estimate) {
        metrics::StampedPose g = p;
        g.p = turn * p.p + Eigen::Vector3d(1, 2, 3);
        g.q = turn * p.q;
        gt.push_back(g);
    }
    metrics::Protocol protocol;
    RunRecord run;
    run.dir = dir.path();
    run.ok = true;
    run.cell.id = "0123456789abcdef";
    run.cell.algorithm = run.cell.plugin = "put_vo";
    run.cell.dataset = "sim";
    run.cell.sequence = "</script><b>x";
    run.evaluation = metrics::evaluate(gt, tr.estimate, protocol);
    const auto view = cell_view(run, ViewLimits{25, 25, 25});
    REQUIRE(view);
    const auto& v = *view;
    CHECK(v["poses"] == 40);
    CHECK(v["shown"].get<std::size_t>() <= 25);
    const auto& est = v["tracks"][1];
    const auto& ref = v["tracks"][0];
    CHECK(est["role"] == "estimate");
    REQUIRE(est["q"].size() == 4 * v["shown"].get<std::size_t>());
    for (std::size_t k = 0; k < v["shown"].get<std::size_t>(); ++k) {
        const Eigen::Quaterniond qe(est["q"][4 * k], est["q"][4 * k + 1], est["q"][4 * k + 2], est["q"][4 * k + 3]);
        const Eigen::Quaterniond qg(ref["q"][4 * k], ref["q"][4 * k + 1], ref["q"][4 * k + 2], ref["q"][4 * k + 3]);
        CHECK(qe.angularDistance(qg) < 1e-4);  // exact data: the aligned orientation is the ground truth's
        for (int a = 0; a < 3; ++a) CHECK(est["p"][3 * k + a].get<double>() == Approx(ref["p"][3 * k + a].get<double>()).margin(2e-5));
        CHECK(est["err"][k].get<double>() < 1e-6);
    }
    REQUIRE(v.contains("timing"));
    CHECK(v["timing"]["rows"] == 40);
    CHECK(v["timing"]["bucket"] == 2);  // 40 rows, at most 25 shown: means of two
    CHECK(v["timing"]["process"][0].get<double>() == Approx(2.0005).epsilon(1e-3));
    CHECK(v["rpe"]["pairs"].get<std::size_t>() > 25);
    CHECK(v["rpe"]["shown"].get<std::size_t>() <= 25);

    // The island: every string stays inside its JSON string, and it parses back to the same data.
    const std::string page = interactive_scripts({{"kind", "report"}, {"views", nlohmann::json::array({v})}});
    const std::string open = "<script type=\"application/json\" id=\"vobench-data\">";
    const std::size_t from = page.find(open) + open.size(), to = page.find("</script>", from);
    const std::string island = page.substr(from, to - from);
    CHECK(island.find('<') == std::string::npos);
    CHECK(island.find('>') == std::string::npos);
    CHECK(nlohmann::json::parse(island)["views"][0]["row"] == "sim/</script><b>x");
    CHECK(page.find(std::string(plotly_js().substr(0, 200))) != std::string::npos);
}

TEST_CASE("the embedded plotly.js is the pinned build, whole", "[report][interactive]") {
    const std::string_view js = plotly_js();
    CHECK(js.size() > 1'000'000);
    CHECK(js.find("plotly.js (gl3d - minified) v4.1.1") != std::string_view::npos);
    CHECK(js.find("Licensed under the MIT license") != std::string_view::npos);
    CHECK(js.substr(js.size() - 200).find("window.Plotly = Plotly") != std::string_view::npos);
    CHECK(report_app_js().find("vobench-data") != std::string_view::npos);
}
