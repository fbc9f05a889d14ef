#include "abi/instances.hpp"
#include "abi/plugin_library.hpp"
#include "abi/plugin_registry.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <vector>

using namespace vobench;
using Catch::Matchers::Contains;

namespace {

std::string load_error(const std::filesystem::path& path) {
    try {
        PluginLibrary::load(path);
    } catch (const PluginLoadError& e) {
        return e.what();
    }
    return "";
}

double process_x(OdometryInstance& odo, uint64_t index) {
    test::TinyFrame f;
    f.frame.index = index;
    vobench_pose pose{};
    pose.struct_size = sizeof(pose);
    vobench_tracking_status tracking;
    REQUIRE(odo.process(f.frame, pose, tracking) == VOBENCH_OK);
    return pose.tx;
}

const vobench_camera& kCamera = test::kTinyCamera;

}  // namespace

TEST_CASE("the loader refuses broken libraries with a one-line reason", "[abi][loader]") {
    using test::fault_plugin;
    CHECK_THAT(load_error(fault_plugin("fault_no_entry")), Contains("not a vobench plugin (no vobench_plugin_entry_v1"));
    CHECK_THAT(load_error(fault_plugin("fault_wrong_abi")),
               Contains("built for plugin ABI 2 (exports vobench_plugin_entry_v2), this host speaks ABI 1"));
    CHECK_THAT(load_error(fault_plugin("fault_null_descriptor")), Contains("returned no descriptor"));
    CHECK_THAT(load_error(fault_plugin("fault_bad_struct_size")), Contains("descriptor struct_size 8 is smaller than"));
    CHECK_THAT(load_error(fault_plugin("fault_bad_param_default")),
               Contains("parameter 'gain': default 'not-a-number' is not a finite number"));
    CHECK_THAT(load_error(fault_plugin("fault_null_function")), Contains("odometry table has a NULL function"));
    CHECK_THAT(load_error("/nonexistent/plugin.so"), Contains("no such file"));

    test::TempDir dir;
    const auto fake = dir.path() / "not_a_library.so";
    std::ofstream(fake) << "this is text, not ELF\n";
    const std::string why = load_error(fake);
    CHECK_THAT(why, Contains("cannot be loaded as a shared library"));
    CHECK_THAT(why, Contains(fake.string()));
    CHECK(why.find('\n') == std::string::npos);
}

TEST_CASE("a valid plugin loads and its descriptor is exposed", "[abi][loader]") {
    const PluginPtr p = PluginLibrary::load(test::fault_plugin("vobench_counter"));
    CHECK(p->name() == "counter");
    CHECK(p->kind() == VOBENCH_KIND_ODOMETRY);
    REQUIRE(p->params().size() == 2);
    CHECK(p->params()[0].name == "start");
    CHECK(p->params()[0].type == VOBENCH_PARAM_INT);
}

TEST_CASE("two instances of one plugin in one process do not interfere", "[abi][loader]") {
    const PluginPtr p = PluginLibrary::load(test::fault_plugin("vobench_counter"));
    OdometryInstance a(p), b(p);
    a.start(kCamera, {{"start", "0"}}, 1);
    b.start(kCamera, {{"start", "100"}}, 1);
    CHECK(process_x(a, 0) == 1.0);
    CHECK(process_x(b, 0) == 101.0);
    CHECK(process_x(a, 1) == 2.0);
    CHECK(process_x(a, 2) == 3.0);
    CHECK(process_x(b, 1) == 102.0);
    a.reset();
    CHECK(process_x(a, 3) == 1.0);
    CHECK(process_x(b, 2) == 103.0);
}

TEST_CASE("an instance keeps its library loaded after the last other reference is gone", "[abi][loader]") {
    std::unique_ptr<OdometryInstance> odo;
    {
        PluginPtr p = PluginLibrary::load(test::fault_plugin("vobench_counter"));
        odo = std::make_unique<OdometryInstance>(p);
    }
    odo->start(kCamera, {}, 1);
    CHECK(process_x(*odo, 0) == 1.0);  // would crash if the code had been unmapped
}

TEST_CASE("host-side parameter validation names the plugin and the parameter", "[abi][params]") {
    const PluginPtr p = PluginLibrary::load(test::fault_plugin("vobench_counter"));
    OdometryInstance odo(p);
    CHECK_THROWS_WITH(odo.start(kCamera, {{"strat", "1"}}, 1),
                      Contains("plugin 'counter' has no parameter 'strat' (it has: start, throw_at)"));
    CHECK_THROWS_WITH(odo.start(kCamera, {{"start", "5000"}}, 1),
                      Contains("plugin 'counter', parameter 'start': '5000' is outside [-1000, 1000]"));
    CHECK_THROWS_WITH(odo.start(kCamera, {{"start", "1.5"}}, 1), Contains("'1.5' is not an integer"));
}

TEST_CASE("stage timing and counters reach the host", "[abi][host]") {
    const PluginPtr p = PluginLibrary::load(test::fault_plugin("vobench_counter"));
    OdometryInstance odo(p);
    odo.start(kCamera, {}, 1);
    odo.host().begin_call();
    process_x(odo, 0);
    REQUIRE(odo.host().stage_ns().size() == 1);
    CHECK(odo.host().stage_ns()[0].first == "count");
    CHECK(odo.host().stage_ns()[0].second >= 0);
    REQUIRE(odo.host().counters().size() == 1);
    CHECK(odo.host().counters()[0] == std::make_pair(std::string("count"), 1.0));
    CHECK(odo.host().unbalanced_stages() == 0);
}

TEST_CASE("the registry finds plugins by name and reports refusals", "[abi][registry]") {
    const PluginRegistry registry({VOBENCH_FAULT_PLUGIN_DIR, VOBENCH_PLUGIN_DIR});
    const PluginScan scan = registry.scan();
    std::vector<std::string> names;
    for (const auto& p : scan.plugins) names.push_back(p.name);
    CHECK(std::find(names.begin(), names.end(), "counter") != names.end());
    CHECK(std::find(names.begin(), names.end(), "tum") != names.end());
    CHECK(std::find(names.begin(), names.end(), "constant_pose") != names.end());
    CHECK(scan.refusals.size() >= 6);  // the fault plugins
    CHECK(registry.describe("tum", VOBENCH_KIND_DATASET).name == "tum");
    CHECK(registry.load("tum", VOBENCH_KIND_DATASET)->name() == "tum");
    CHECK_THROWS_WITH(registry.describe("tum", VOBENCH_KIND_ODOMETRY), Contains("is a dataset plugin, not a odometry plugin"));
    CHECK_THROWS_WITH(registry.describe("no_such_plugin"), Contains("no plugin named 'no_such_plugin'"));
}
