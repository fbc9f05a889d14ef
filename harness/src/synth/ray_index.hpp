// ray_index.hpp — the office's boxes as triangles in Intel Embree (3.x, Debian libembree-dev), the
// ray caster the renderer's colour, depth and shadow rays go through. Embree builds its own bounding
// volume hierarchy and traces single rays with SIMD; a box is 12 triangles, and a hit's primitive
// number tells the box and its face.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace vobench::synth {

struct Box;

struct IndexHit {
    double t = 0;
    int box = -1;
    int axis = 0;           // the face's normal axis
    bool max_side = false;  // the face at box.max[axis] (else at box.min[axis])
};

class RayIndex {
public:
    // Copies the boxes' geometry (single precision: ~1 µm at 10 m). Throws std::runtime_error when
    // Embree cannot start (its message included).
    explicit RayIndex(const std::vector<Box>& boxes);
    ~RayIndex();
    RayIndex(const RayIndex&) = delete;
    RayIndex& operator=(const RayIndex&) = delete;

    // Nearest face along origin + t·dir with t in (t_min, t_max); thread-safe.
    bool nearest(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_min, double t_max, IndexHit& hit) const;
    // Whether anything lies on the ray within (t_min, t_max).
    bool any(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_min, double t_max) const;

private:
    struct Handles;
    std::unique_ptr<Handles> handles_;
};

}  // namespace vobench::synth
