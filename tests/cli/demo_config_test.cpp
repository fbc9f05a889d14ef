#include "run/demo_config.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>

using namespace vobench;
using Catch::Matchers::Contains;

namespace {

std::string error_of(const std::string& yaml) {
    test::TempDir dir;
    const auto file = dir.path() / "demo.yaml";
    std::ofstream(file) << yaml;
    try {
        load_demo_config(file, PluginRegistry({VOBENCH_PLUGIN_DIR}));
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

const char* kGood = "seed: 3\nframes: 20\nsequences:\n  - {sensor: kinect1, trajectory: explore2}\nalgorithms:\n  - {plugin: put_vo, params: {keyframe_interval: 2}}\n";

}  // namespace

TEST_CASE("the shipped quickstart configuration is valid", "[config]") {
    const DemoConfig c = load_demo_config(std::filesystem::path(VOBENCH_SOURCE_DIR) / "configs" / "quickstart.yaml",
                                          PluginRegistry({VOBENCH_PLUGIN_DIR}));
    CHECK(c.sequences.size() == 4);
    CHECK(c.algorithms.size() == 3);
    CHECK(c.algorithms[1].params.at("method") == "rgbd");
}

TEST_CASE("configuration errors name file, line and column", "[config]") {
    CHECK(error_of(kGood).empty());
    CHECK_THAT(error_of("sede: 3\n"), Contains("demo.yaml:1:1: unknown key 'sede' in the configuration"));
    CHECK_THAT(error_of("frames: ten\nsequences: []\n"), Contains("demo.yaml:1:9: frames: 'ten' is not of the expected type"));
    CHECK_THAT(error_of("sequences:\n  - {sensor: kinect3, trajectory: explore1}\nalgorithms: [{plugin: put_vo}]\n"),
               Contains("demo.yaml:2:14: sensor 'kinect3' is not kinect1 or kinect2"));
    CHECK_THAT(error_of("sequences:\n  - {sensor: kinect1, trajectory: explore1}\nalgorithms:\n  - {plugin: no_such_vo}\n"),
               Contains("demo.yaml:4:14: no plugin named 'no_such_vo'"));
    CHECK_THAT(error_of("sequences:\n  - {sensor: kinect1, trajectory: explore1}\nalgorithms:\n  - {plugin: put_vo, params: {keyframe_interval: 0}}\n"),
               Contains("demo.yaml:4:31: plugin 'put_vo', parameter 'keyframe_interval': '0' is outside [1, 100]"));
    CHECK_THAT(error_of("sequences: [\n"), Contains("demo.yaml:"));
}
