#include "abi/instances.hpp"
#include "test_support.hpp"

#include <vobench/plugin.hpp>

#include <catch2/catch.hpp>

using namespace vobench;
using Catch::Matchers::Contains;

TEST_CASE("an exception thrown in plugin code becomes an error status with its message", "[sdk]") {
    OdometryInstance odo(PluginLibrary::load(test::fault_plugin("vobench_counter")));
    odo.start(test::kTinyCamera, {{"throw_at", "1"}}, 1);
    test::TinyFrame tiny;
    vobench_frame& frame = tiny.frame;
    vobench_pose pose{};
    pose.struct_size = sizeof(pose);
    vobench_tracking_status tracking;
    REQUIRE(odo.process(frame, pose, tracking) == VOBENCH_OK);
    frame.index = 1;
    CHECK(odo.process(frame, pose, tracking) == VOBENCH_ERROR);
    CHECK(odo.last_error() == "deliberate failure at frame 1");
}

TEST_CASE("the SDK writes only the pose fields the host's struct covers", "[sdk]") {
    OdometryInstance odo(PluginLibrary::load(test::fault_plugin("vobench_counter")));
    odo.start(test::kTinyCamera, {}, 1);
    test::TinyFrame tiny;
    const vobench_frame& frame = tiny.frame;
    // An older host whose pose ends after tx: the fields past it must stay untouched.
    vobench_pose pose{};
    pose.struct_size = static_cast<uint32_t>(offsetof(vobench_pose, ty));
    pose.ty = -7.0;
    vobench_tracking_status tracking;
    REQUIRE(odo.process(frame, pose, tracking) == VOBENCH_OK);
    CHECK(pose.tx == 1.0);
    CHECK(pose.ty == -7.0);
    CHECK(pose.struct_size == offsetof(vobench_pose, ty));
}

TEST_CASE("parameter parsing rules shared by host and SDK", "[sdk][params]") {
    sdk::Param p{"x", VOBENCH_PARAM_DOUBLE, "1", 0.0, 2.0, "", "h"};
    CHECK(sdk::check_param_value(p, "1.5").empty());
    CHECK_THAT(sdk::check_param_value(p, "2.5"), Contains("outside"));
    CHECK_THAT(sdk::check_param_value(p, "nan"), Contains("not a finite number"));
    CHECK_THAT(sdk::check_param_value(p, "1.5x"), Contains("not a finite number"));
    sdk::Param e{"m", VOBENCH_PARAM_ENUM, "a", 0, 0, "a|bb|c", "h"};
    CHECK(sdk::check_param_value(e, "bb").empty());
    CHECK_FALSE(sdk::check_param_value(e, "b").empty());
    CHECK_FALSE(sdk::check_param_value(e, "a|bb").empty());
    sdk::Param b{"f", VOBENCH_PARAM_BOOL, "true", 0, 0, "", "h"};
    CHECK(sdk::check_param_value(b, "off").empty());
    CHECK_FALSE(sdk::check_param_value(b, "maybe").empty());
}

TEST_CASE("Params::with_defaults: a profile's defaults replace the table's, a given value still wins", "[sdk][params]") {
    const std::vector<sdk::Param> table{{"n", VOBENCH_PARAM_INT, "350", 1, 1000, "", "h"},
                                        {"kind", VOBENCH_PARAM_ENUM, "fast", 0, 0, "fast|orb", "h"},
                                        {"on", VOBENCH_PARAM_BOOL, "true", 0, 0, "", "h"}};
    const char* keys[] = {"kind"};
    const char* values[] = {"fast"};
    const vobench_params given{sizeof(vobench_params), 1, keys, values};
    const sdk::Params p(table, &given);
    CHECK(p.given("kind"));
    CHECK_FALSE(p.given("n"));
    const sdk::Params q = p.with_defaults({{"n", "500"}, {"kind", "orb"}});
    CHECK(q.get_int("n") == 500);           // not given: the profile's
    CHECK(q.get_string("kind") == "fast");  // given, even as the table's own default: kept
    CHECK(q.get_bool("on"));                // in no profile: the table's
    CHECK(p.get_int("n") == 350);           // the original is untouched
    CHECK_THROWS_WITH(p.with_defaults({{"m", "1"}}), Contains("undeclared parameter 'm'"));
    CHECK_THROWS_WITH(p.with_defaults({{"n", "5000"}}), Contains("default for 'n'"));
}
