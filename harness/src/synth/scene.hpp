// scene.hpp — what the renderer sees: axis-aligned boxes with their materials, and point lights;
// ray casting (through Embree, ray_index.hpp) and shading. office.hpp builds the office around a
// trajectory.
//
// The world frame is that of PUTK²'s ground truth (the central ceiling camera's frame): x and y span
// the floor, z points down, the ceiling cameras sit at z = 0. The floor is at z = floor_z.
#pragma once

#include "synth/texture.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <vector>

namespace vobench::synth {

class RayIndex;

struct Box {
    Eigen::Vector3d min, max;
    int material = 0;    // index into Scene::materials; for the room shell, + face (0..5)
    bool shell = false;  // the room itself: seen from inside
};

struct Hit {
    double t = 0;  // distance along the (unit) ray
    Eigen::Vector3d point;
    Eigen::Vector3d normal;  // facing the ray origin: ±1 on `axis`, 0 on the other two
    int axis = 0;            // the normal's axis (every surface is a face of an axis-aligned box)
    int material = -1;
    double u = 0, v = 0;  // surface coordinates, metres
};

struct PointLight {
    Eigen::Vector3d position;
    double power;
};

struct Scene {
    std::vector<Box> boxes;
    std::vector<Material> materials;
    std::vector<PointLight> lights;
    double floor_z = 3.0;

    // Nearest hit of the ray origin + t·dir (dir unit), t in (t_min, t_max); false when none. Goes
    // through Embree once build_index() has run (after the last change to `boxes`), else tests every
    // box (slabs; small test scenes).
    bool intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_min, double t_max, Hit& hit) const;
    // The nearest hits of `count` rays from one origin (a run of pixels in an image row), traced in
    // packets of RayIndex::kPacket; found[i] says whether ray i hit. What `intersect` finds ray by ray, up to
    // float rounding (ray_index.hpp).
    void intersect_packet(const Eigen::Vector3d& origin, const Eigen::Vector3d* dirs, int count, double t_min, double t_max, Hit* hits,
                          bool* found) const;
    void build_index();
    // True when anything blocks the segment from `from` towards `to` (shadow rays).
    bool occluded(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;
    // Linear RGB radiance seen along `view_dir` (unit, towards the surface) at `hit`, with pixel
    // footprint (m) for filtering: ambient + diffuse point lights, Blinn–Phong highlights on glossy
    // materials, emission (windows).
    Eigen::Vector3f shade(const Hit& hit, const Eigen::Vector3d& view_dir, double footprint, bool highlights = true) const;

private:
    // The hit record of the face `axis` (on the side the ray meets) of box `box` at distance t.
    Hit hit_on(int box, int axis, bool positive_side, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t) const;
    std::shared_ptr<const RayIndex> index_;  // shared by copies of the scene
};

}  // namespace vobench::synth
