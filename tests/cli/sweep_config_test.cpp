#include "sweep/sweep_config.hpp"
#include "sweep/cell.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>

using namespace vobench;
using Catch::Matchers::Contains;

namespace {

PluginRegistry registry() { return PluginRegistry({VOBENCH_PLUGIN_DIR}); }

std::string error_of(const std::string& yaml) {
    test::TempDir dir;
    const auto file = dir.path() / "sweep.yaml";
    std::ofstream(file) << yaml;
    try {
        load_sweep_config(file, registry());
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

SweepConfig load(const test::TempDir& dir, const std::string& yaml) {
    const auto file = dir.path() / "sweep.yaml";
    std::ofstream(file) << yaml;
    return load_sweep_config(file, registry());
}

const std::string kData = "datasets:\n  - {name: sim, synthetic: {trajectories: [explore1], sensors: [kinect1, kinect2], frames: 20}}\n";

}  // namespace

TEST_CASE("the shipped configurations are valid", "[config]") {
    const auto dir = std::filesystem::path(VOBENCH_SOURCE_DIR) / "configs";
    const SweepConfig q = load_sweep_config(dir / "quickstart.yaml", registry());
    CHECK(q.datasets.size() == 1);
    CHECK(q.datasets[0].synthetic->sensors == std::vector<std::string>{"kinect1", "kinect2"});
    CHECK(q.algorithms.size() == 3);
    CHECK(q.algorithms[1].variants.at(0).at("method") == "rgbd");
    // The others name data that lives elsewhere: their paths are checked only when running.
    for (const char* name : {"paper_table5.yaml", "tum.yaml", "icl_nuim.yaml"}) {
        INFO(name);
        const SweepConfig c = load_sweep_config(dir / name, registry(), false);
        CHECK(!c.datasets.empty());
        CHECK(!c.algorithms.empty());
    }
    const SweepConfig t5 = load_sweep_config(dir / "paper_table5.yaml", registry(), false);
    REQUIRE(t5.datasets.size() == 1);
    CHECK(t5.datasets[0].sequences.size() == 8);  // PUTK² sequences 1-8
    CHECK(t5.datasets[0].sensors == std::vector<std::string>{"kinect1", "kinect2"});
}

TEST_CASE("paper_table5_sim.yaml names the eight real PUTK² marker trajectories", "[config]") {
    VOBENCH_REQUIRE_DATA(gt_dir, "putk2-groundtruth");
    ::setenv("VOBENCH_PUTK2_GT", gt_dir.c_str(), 1);
    const SweepConfig c = load_sweep_config(std::filesystem::path(VOBENCH_SOURCE_DIR) / "configs" / "paper_table5_sim.yaml", registry());
    ::unsetenv("VOBENCH_PUTK2_GT");
    REQUIRE(c.datasets.size() == 1);
    REQUIRE(c.datasets[0].synthetic);
    CHECK(c.datasets[0].synthetic->trajectories.size() == 8);
    CHECK(c.datasets[0].synthetic->trajectories[0] == (gt_dir / "trajectory2.txt").string());
    CHECK(c.datasets[0].synthetic->names[0] == "seq1");
    CHECK(c.datasets[0].synthetic->names[7] == "seq8");
    CHECK(c.datasets[0].sensors == std::vector<std::string>{"kinect1", "kinect2"});
}

TEST_CASE("configuration errors name file, line and column", "[config]") {
    const std::string algo = "algorithms:\n  - {plugin: put_vo}\n";
    CHECK(error_of(kData + algo).empty());
    CHECK_THAT(error_of("sede: 3\n"), Contains("sweep.yaml:1:1: unknown key 'sede' in the configuration"));
    CHECK_THAT(error_of("frames: ten\n" + kData + algo), Contains("sweep.yaml:1:9: frames: 'ten' is not of the expected type"));
    CHECK_THAT(error_of("datasets:\n  - {name: s, synthetic: {trajectories: [explore1], sensors: [kinect3]}}\n" + algo),
               Contains("sweep.yaml:2:62: sensor 'kinect3' is not kinect1 or kinect2"));
    CHECK_THAT(error_of(kData + "algorithms:\n  - {plugin: no_such_vo}\n"), Contains("sweep.yaml:4:14: no plugin named 'no_such_vo'"));
    CHECK_THAT(error_of(kData + "algorithms:\n  - {plugin: put_vo, params: {keyframe_interval: 0}}\n"),
               Contains("sweep.yaml:4:31: plugin 'put_vo', parameter 'keyframe_interval': '0' is outside [1, 100]"));
    CHECK_THAT(error_of(kData + "algorithms:\n  - plugin: put_vo\n    grid: {keyframe_interval: [2, 200]}\n"),
               Contains("sweep.yaml:5:35: plugin 'put_vo', parameter 'keyframe_interval': '200' is outside [1, 100]"));
    CHECK_THAT(error_of(kData + "algorithms:\n  - plugin: put_vo\n    grid: {no_such: [1]}\n"),
               Contains("sweep.yaml:5:22: plugin 'put_vo' has no parameter 'no_such'"));
    CHECK_THAT(error_of("datasets:\n  - {name: t, reader: tum, path: /no/such/folder}\n" + algo),
               Contains("sweep.yaml:2:34: no such sequence folder: /no/such/folder"));
    CHECK_THAT(error_of(kData + algo + "limits: {timeout: 0}\n"), Contains("sweep.yaml:5:19: timeout must be at least 1 s"));
    CHECK_THAT(error_of(kData + algo + "rank_by: speed\n"), Contains("sweep.yaml:5:10: rank_by: unknown metric 'speed'"));
    CHECK_THAT(error_of(kData + algo + "criteria: ['ate.rmse <== 1']\n"),
               Contains("sweep.yaml:5:12: criterion 'ate.rmse <== 1' is not of the form"));
    CHECK_THAT(error_of(kData + algo + "protocol: {alignment: affine}\n"), Contains("unknown alignment 'affine'"));
    CHECK_THAT(error_of("datasets: [\n"), Contains("sweep.yaml:"));
}

TEST_CASE("grid, zip and ranges expand into parameter variants", "[config]") {
    test::TempDir dir;
    const SweepConfig c = load(dir, kData +
                                        "algorithms:\n"
                                        "  - plugin: put_vo\n"
                                        "    params: {lk_levels: 2}\n"
                                        "    grid: {keyframe_interval: {from: 2, to: 6, step: 2}, redetect_below: [100, 150]}\n"
                                        "    zip: {lk_fb_threshold: [0.5, 1.0], depth_weighting: [false, true]}\n");
    const auto& v = c.algorithms.at(0).variants;
    REQUIRE(v.size() == 3 * 2 * 2);
    CHECK(v[0].at("lk_levels") == "2");
    CHECK(v[0].at("keyframe_interval") == "2");
    CHECK(v[0].at("redetect_below") == "100");
    CHECK(v[0].at("lk_fb_threshold") == "0.5");
    CHECK(v[0].at("depth_weighting") == "false");
    CHECK(v[1].at("lk_fb_threshold") == "1.0");
    CHECK(v[1].at("depth_weighting") == "true");
    CHECK(v.back().at("keyframe_interval") == "6");
    CHECK(v.back().at("redetect_below") == "150");
}

TEST_CASE("environment variables in paths", "[config]") {
    ::setenv("VOBENCH_TEST_X", "/data", 1);
    ::unsetenv("VOBENCH_TEST_UNSET");
    CHECK(expand_env("${VOBENCH_TEST_X}/tum") == "/data/tum");
    CHECK(expand_env("${VOBENCH_TEST_UNSET:-datasets}/tum") == "datasets/tum");
    CHECK(expand_env("${VOBENCH_TEST_UNSET}/tum") == "/tum");
}

TEST_CASE("criteria parse and name unknown metrics", "[config]") {
    const Criterion c = parse_criterion("rpe.trans.rmse <= 0.02");
    CHECK(c.metric == "rpe.trans.rmse");
    CHECK(c.op == "<=");
    CHECK(c.value == 0.02);
    CHECK_THROWS_WITH(parse_criterion("speed >= 3"), Contains("unknown metric 'speed'"));
}
