// The office where a camera is held over a desk (office.cpp, desk_clutter.cpp): the desk under its gaze
// is a top on four legs, open beneath as real desks are, and the room is as large as the camera asks.
#include "synth/office.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace vobench::synth;

namespace {

// A camera 1.55 m above the floor (TUM's fr1/rpy is held at 1.52–1.58 m) looking 40° down and turning
// slowly about the vertical: its gaze meets desk height (0.72–0.76 m) about 0.97 m ahead. World z is
// down, the floor at z = floor_z; the camera's z looks ahead, its y points down the image.
std::vector<Eigen::Isometry3d> held_over_a_desk(double floor_z) {
    const double down = 40 * M_PI / 180;
    std::vector<Eigen::Isometry3d> poses;
    for (int k = 0; k < 30; ++k) {
        const double yaw = 0.005 * k;
        const Eigen::Vector3d ahead(std::cos(yaw) * std::cos(down), std::sin(yaw) * std::cos(down), std::sin(down));
        const Eigen::Vector3d image_down(-std::cos(yaw) * std::sin(down), -std::sin(yaw) * std::sin(down), std::cos(down));
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear().col(0) = image_down.cross(ahead);
        pose.linear().col(1) = image_down;
        pose.linear().col(2) = ahead;
        pose.translation() = Eigen::Vector3d(0, 0, floor_z - 1.55);
        poses.push_back(pose);
    }
    return poses;
}

bool contains(const Box& b, const Eigen::Vector3d& p) { return (p.array() > b.min.array()).all() && (p.array() < b.max.array()).all(); }

}  // namespace

TEST_CASE("the desk a camera is held over is a 3-cm top on four legs, open beneath", "[synth][office]") {
    for (const uint64_t seed : {1, 2, 3}) {
        OfficeOptions options;
        options.seed = seed;
        const auto poses = held_over_a_desk(options.floor_z);
        const Scene scene = build_office(poses, options);
        const double floor = options.floor_z;
        // Where the first pose's gaze meets desk height, a desk top: a slab 3 cm thick at 0.72–0.76 m.
        const Eigen::Vector3d at = poses[0].translation(), ahead = poses[0].linear().col(2);
        const Eigen::Vector3d gaze = at + ahead * ((floor - 0.74 - at.z()) / ahead.z());
        const Box* top = nullptr;
        for (const Box& b : scene.boxes)
            if (!b.shell && std::abs(b.max.z() - b.min.z() - 0.03) < 1e-9 && b.min.x() < gaze.x() && gaze.x() < b.max.x() &&
                b.min.y() < gaze.y() && gaze.y() < b.max.y())
                top = &b;
        INFO("seed " << seed << ", gaze at (" << gaze.x() << ", " << gaze.y() << ")");
        REQUIRE(top != nullptr);
        CHECK(floor - top->min.z() >= 0.72);
        CHECK(floor - top->min.z() <= 0.76);
        CHECK(std::min(top->max.x() - top->min.x(), top->max.y() - top->min.y()) >= 0.7);
        // Open beneath: nothing fills the space under the top's middle (a solid block did), and four
        // 4-cm legs stand from its underside to the floor.
        const Eigen::Vector3d centre = (top->min + top->max) / 2;
        for (const double height : {0.1, 0.4, 0.65})
            for (const Box& b : scene.boxes) CHECK_FALSE((!b.shell && contains(b, {centre.x(), centre.y(), floor - height})));
        int legs = 0;
        for (const Box& b : scene.boxes)
            legs += !b.shell && std::abs(b.max.x() - b.min.x() - 0.04) < 1e-9 && std::abs(b.max.y() - b.min.y() - 0.04) < 1e-9 &&
                    std::abs(b.min.z() - top->max.z()) < 1e-9 && std::abs(b.max.z() - floor) < 1e-9 && b.min.x() >= top->min.x() &&
                    b.max.x() <= top->max.x() && b.min.y() >= top->min.y() && b.max.y() <= top->max.y();
        CHECK(legs == 4);
    }
}

TEST_CASE("the office is at least as wide and long as the camera asks (tum-fr1: its lab is a hall)", "[synth][office]") {
    for (const double min_room : {6.0, 9.0}) {
        OfficeOptions options;
        options.min_room = min_room;
        const Scene scene = build_office(held_over_a_desk(options.floor_z), options);
        REQUIRE(scene.boxes.front().shell);
        const Box& room = scene.boxes.front();
        INFO("asked " << min_room << " m, got " << room.max.x() - room.min.x() << " × " << room.max.y() - room.min.y() << " m");
        CHECK(room.max.x() - room.min.x() >= min_room);
        CHECK(room.max.y() - room.min.y() >= min_room);
        CHECK(room.max.x() - room.min.x() <= 1.3 * min_room + 2.5);  // the path's extent plus margins at most
    }
}
