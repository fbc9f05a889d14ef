// The public header compiles as C++17 too (this file includes it first, before anything else).
#include <vobench/vobench_plugin.h>
#include <vobench/plugin.hpp>

#include <catch2/catch.hpp>

#include <type_traits>

TEST_CASE("the C header is usable from C++: plain, standard-layout structs", "[abi]") {
    STATIC_REQUIRE(std::is_standard_layout_v<vobench_plugin_descriptor>);
    STATIC_REQUIRE(std::is_trivially_copyable_v<vobench_frame>);
    STATIC_REQUIRE(std::is_trivially_copyable_v<vobench_pose>);
    STATIC_REQUIRE(offsetof(vobench_odometry_api, struct_size) == 0);
    vobench_pose pose{};
    pose.struct_size = sizeof(pose);
    REQUIRE(VOBENCH_HAS_FIELD(&pose, vobench_pose, qw));
}
