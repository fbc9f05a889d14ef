// Scene::shade (scene.cpp) against its lighting model written out in full: ambient 0.12 plus the
// material's emission, each point light's power / (1 + 0.3·d²) · max(0, n·l), and on glossy materials
// Blinn–Phong highlights 3·gloss·Σ falloff·max(0, n·h)⁶⁰ (Blinn 1977), h the normalised half vector.
// The renderer takes the normal's one non-zero axis instead of whole dot products and x⁶⁰ by squaring;
// here every dot product is whole and the power is std::pow.
#include "synth/random_field.hpp"
#include "synth/scene.hpp"
#include "synth/texture.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace vobench::synth;

namespace {

Eigen::Vector3f shade_in_full(const Scene& s, const Hit& hit, const Eigen::Vector3d& view_dir, double footprint, bool highlights) {
    const Material& m = s.materials[static_cast<std::size_t>(hit.material)];
    double light = 0.12 + m.emission, specular = 0;
    for (const PointLight& l : s.lights) {
        const Eigen::Vector3d to = l.position - hit.point;
        const Eigen::Vector3d l_dir = to.normalized();
        const double falloff = l.power / (1.0 + 0.3 * to.squaredNorm());
        light += falloff * std::max(0.0, hit.normal.dot(l_dir));
        if (highlights && m.gloss > 0) specular += falloff * std::pow(std::max(0.0, hit.normal.dot((l_dir - view_dir).normalized())), 60.0);
    }
    return albedo(m, hit.u, hit.v, footprint) * static_cast<float>(light) +
           Eigen::Vector3f::Constant(static_cast<float>(3.0 * m.gloss * specular));
}

Eigen::Vector3d random_point(uint64_t h, double half_size) {
    return Eigen::Vector3d(2 * uniform(mix64(h)) - 1, 2 * uniform(mix64(h + 1)) - 1, 2 * uniform(mix64(h + 2)) - 1) * half_size;
}

}  // namespace

TEST_CASE("shading is ambient, diffuse point lights and Blinn–Phong highlights, on every face of a box", "[synth][shading]") {
    Scene s;
    Material matte;
    matte.seed = 3;
    Material glossy = matte;
    glossy.style = TextureStyle::Photo;
    glossy.gloss = 0.4f;
    Material lamp = matte;
    lamp.style = TextureStyle::Tiles;
    lamp.emission = 0.3f;
    s.materials = {matte, glossy, lamp};
    // Three boxes in a row; lights all around them, so every face has lights in front and behind.
    for (int k = 0; k < 3; ++k) {
        Box b;
        b.min = Eigen::Vector3d(-1.5 + 1.1 * k, -0.4, -0.3);
        b.max = b.min + Eigen::Vector3d(0.8, 0.8, 0.6);
        b.material = k;
        s.boxes.push_back(b);
    }
    for (uint64_t k = 0; k < 7; ++k) s.lights.push_back({random_point(hash(11, k), 3.0), 0.2 + 0.1 * static_cast<double>(k)});

    int hits = 0, highlighted = 0, behind = 0;
    for (uint64_t k = 0; k < 3000; ++k) {
        const Eigen::Vector3d origin = random_point(hash(5, k), 4.0);
        const Eigen::Vector3d dir = (random_point(hash(7, k), 1.0) - origin).normalized();
        Hit hit;
        if (!s.intersect(origin, dir, 1e-6, 100.0, hit)) continue;
        ++hits;
        const double footprint = 1e-3 * hit.t;
        for (const bool highlights : {true, false}) {
            const Eigen::Vector3f shaded = s.shade(hit, dir, footprint, highlights);
            const Eigen::Vector3f expected = shade_in_full(s, hit, dir, footprint, highlights);
            for (int c = 0; c < 3; ++c) REQUIRE(shaded[c] == Approx(expected[c]).epsilon(1e-6).margin(1e-12));
        }
        const Eigen::Vector3f diffuse_only = shade_in_full(s, hit, dir, footprint, false);
        if (s.materials[static_cast<std::size_t>(hit.material)].gloss > 0 &&
            shade_in_full(s, hit, dir, footprint, true).x() > diffuse_only.x() + 1e-3f)
            ++highlighted;
        for (const PointLight& l : s.lights) behind += hit.normal.dot(l.position - hit.point) < 0 ? 1 : 0;
    }
    // Not vacuous: rays hit, highlights show, and lights stand behind faces that are shaded.
    CHECK(hits > 1000);
    CHECK(highlighted > 50);
    CHECK(behind > 1000);
}
