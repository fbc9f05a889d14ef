// The renderer's packet tracing (RayIndex::nearest_packet, Scene::intersect_packet) against Embree's
// single rays and against the slab test without Embree, in a generated office seen from its path.
#include "synth/ray_index.hpp"
#include "synth/frame_plan.hpp"
#include "synth/office.hpp"
#include "synth/trajectory_families.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <random>

using namespace vobench::synth;

namespace {

struct Office {
    Scene scene;
    std::vector<Eigen::Isometry3d> poses;
    Office() {
        for (const auto& p : family_trajectory("explore1", 1)) poses.push_back(p.isometry());
        OfficeOptions options;
        options.seed = 3;
        const Eigen::Isometry3d to_office = office_from_world(poses, options.floor_z);
        for (auto& p : poses) p = to_office * p;
        scene = build_office(poses, options);
    }
};

}  // namespace

TEST_CASE("packets of rays hit what single rays hit, faces exactly and distances to float precision", "[synth][ray_index]") {
    const Office office;
    REQUIRE(office.scene.boxes.size() > 50);  // an office with clutter, not a shell
    std::mt19937_64 rng(7);
    std::normal_distribution<double> n(0, 1);
    std::uniform_int_distribution<int> count_of(1, 3 * RayIndex::kPacket);
    long rays = 0, same_face = 0, hits = 0;
    for (std::size_t k = 0; k < office.poses.size(); k += 5) {
        const Eigen::Vector3d o = office.poses[k].translation();
        for (int trial = 0; trial < 40; ++trial) {
            // A run of neighbouring directions (a row of pixels), of any length up to three packets.
            const int count = count_of(rng);
            const Eigen::Vector3d start = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
            const Eigen::Vector3d step = Eigen::Vector3d(n(rng), n(rng), n(rng)) * 2e-3;
            std::vector<Eigen::Vector3d> dirs;
            for (int i = 0; i < count; ++i) dirs.push_back((start + i * step).normalized());
            std::vector<Hit> packet(dirs.size());
            std::unique_ptr<bool[]> found(new bool[dirs.size()]);
            office.scene.intersect_packet(o, dirs.data(), count, 1e-6, 1e3, packet.data(), found.get());
            for (int i = 0; i < count; ++i) {
                Hit single;
                const bool hit = office.scene.intersect(o, dirs[static_cast<std::size_t>(i)], 1e-6, 1e3, single);
                ++rays;
                REQUIRE(found[static_cast<std::size_t>(i)] == hit);
                if (!hit) continue;
                ++hits;
                const Hit& p = packet[static_cast<std::size_t>(i)];
                CHECK(std::abs(p.t - single.t) <= 1e-5 * single.t);
                if (p.material == single.material && p.normal == single.normal) ++same_face;
            }
        }
    }
    INFO(rays << " rays, " << hits << " hits, " << same_face << " on the same face");
    CHECK(hits > rays * 9 / 10);  // inside a closed room nearly every ray hits
    // Where a ray grazes an edge, single and packet kernels may round to the neighbouring face.
    CHECK(same_face >= hits - hits / 1000);
}

TEST_CASE("without Embree the packet call falls back to the slab test ray by ray", "[synth][ray_index]") {
    Scene scene;
    Material m;
    scene.materials = {m, m, m, m, m, m, m};
    scene.boxes.push_back({Eigen::Vector3d(-5, -5, -5), Eigen::Vector3d(5, 5, 5), 0, true});
    scene.boxes.push_back({Eigen::Vector3d(1, -1, -1), Eigen::Vector3d(2, 1, 1), 6, false});
    const Eigen::Vector3d dirs[3] = {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(0, 0, 1)};
    Hit hits[3];
    bool found[3];
    scene.intersect_packet(Eigen::Vector3d::Zero(), dirs, 3, 1e-6, 1e3, hits, found);
    CHECK((found[0] && found[1] && found[2]));
    CHECK(hits[0].t == Approx(1.0));
    CHECK(hits[0].material == 6);
    CHECK(hits[1].t == Approx(5.0));
    CHECK(hits[2].t == Approx(5.0));
    scene.build_index();  // the same through Embree
    scene.intersect_packet(Eigen::Vector3d::Zero(), dirs, 3, 1e-6, 1e3, hits, found);
    CHECK(hits[0].t == Approx(1.0));
    CHECK(hits[0].material == 6);
    CHECK(hits[1].t == Approx(5.0));
}
