// renderer.hpp — ray casting of the synthetic office through a sensor model: colour (with lens
// distortion, exposure, noise and motion blur) and depth (with the sensor's noise, holes and
// artefacts), multi-threaded with TBB. Every random number is a hash of (seed, frame, pixel), so the
// output is byte-identical for a seed whatever the thread count.
#pragma once

#include "synth/scene.hpp"
#include "synth/sensor_model.hpp"

#include "depth_registration.hpp"  // plugins/common

#include <opencv2/core.hpp>

#include <vector>

namespace vobench::synth {

struct RenderedFrame {
    cv::Mat color;         // CV_8UC3, BGR, colour camera size
    cv::Mat depth;         // CV_32FC1 metres registered to the colour camera (colour size); 0 = no reading
    cv::Mat depth_native;  // CV_32FC1 metres as the depth camera measures it (its own size and pose)
};

class Renderer {
public:
    Renderer(const Scene& scene, const SensorModel& sensor, uint64_t seed);

    // Renders the frame whose colour camera pose (camera-to-world) is `pose`. `velocity_pose` is the
    // camera pose one frame interval later (or earlier, negated by the caller); with `blur` the colour
    // image integrates the motion over the exposure time (`frame_interval_s` apart from it).
    RenderedFrame render(uint64_t frame_index, const Eigen::Isometry3d& pose, const Eigen::Isometry3d& next_pose, double frame_interval_s,
                         bool blur) const;

    const SensorModel& sensor() const { return sensor_; }

private:
    struct RayMap {
        int width = 0, height = 0;
        std::vector<Eigen::Vector3d> dirs;  // unit ray direction per pixel, camera frame
    };
    static RayMap make_ray_map(const PinholeCamera& camera);
    // Candidate boxes per 16×16 tile for a camera pose (conservative frustum culling).
    std::vector<std::vector<int>> cull(const RayMap& rays, const Eigen::Isometry3d& pose) const;

    void render_color(uint64_t frame, const Eigen::Isometry3d& pose, const Eigen::Isometry3d& next_pose, double frame_interval_s, bool blur,
                      RenderedFrame& out) const;
    struct DepthRay {
        Hit hit;
        double z = 0;          // depth along the depth camera's optical axis
        double incidence = 0;  // angle between ray and surface normal, rad
    };
    // One depth pixel's ray, with lateral jitter; false when it hits nothing.
    bool cast_depth_ray(uint64_t frame, const Eigen::Isometry3d& depth_pose, const std::vector<std::vector<int>>& tiles, int u, int v,
                        DepthRay& out) const;
    void render_depth_structured_light(uint64_t frame, const Eigen::Isometry3d& pose, RenderedFrame& out) const;
    void render_depth_time_of_flight(uint64_t frame, const Eigen::Isometry3d& pose, RenderedFrame& out) const;

    const Scene& scene_;
    SensorModel sensor_;
    uint64_t seed_;
    RayMap color_rays_, depth_rays_;
};

// The registration library's view of a camera.
rgbd::Intrinsics intrinsics_of(const PinholeCamera& camera);

}  // namespace vobench::synth
