// ray_index.hpp — the office's boxes as triangles in Intel Embree (3.x, Debian libembree-dev), the
// ray caster the renderer's colour, depth and shadow rays go through. Embree builds its own bounding
// volume hierarchy and traces rays singly or in packets of 8 (a run of pixels); a box is 12
// triangles, and a hit's primitive number tells the box and its face.
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
    // The nearest faces of up to kPacket rays from one origin (a run of pixels in one image row), traced
    // together as an Embree packet: coherent rays share the walk down the hierarchy. hits[i].box < 0
    // where ray i hits nothing. The faces `nearest` finds ray by ray, the distances to the last float bit
    // (Embree's packet kernels round differently; tested).
    static constexpr int kPacket = 8;
    void nearest_packet(const Eigen::Vector3d& origin, const Eigen::Vector3d* dirs, int count, double t_min, double t_max,
                        IndexHit* hits) const;
    // Whether anything lies on the ray within (t_min, t_max).
    bool any(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_min, double t_max) const;

private:
    struct Handles;
    std::unique_ptr<Handles> handles_;
};

}  // namespace vobench::synth
