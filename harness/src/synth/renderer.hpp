// renderer.hpp — ray casting of the synthetic office through a sensor model: colour (with lens
// distortion, exposure, noise and motion blur) and depth (with the sensor's noise, holes and
// artefacts), multi-threaded with TBB. Every random number is a hash of (seed, frame, pixel), so the
// output is byte-identical for a seed whatever the thread count.
#pragma once

#include "synth/frame_plan.hpp"
#include "synth/random_field.hpp"
#include "synth/scene.hpp"
#include "synth/sensor_model.hpp"

#include "depth_registration.hpp"  // plugins/common

#include <opencv2/core.hpp>

#include <optional>
#include <vector>

namespace vobench::synth {

// Salt values keep the random streams of the renderer's effects apart (random_field.hpp).
enum RenderSalt : uint64_t {
    kColorNoise = 1,
    kDisparityNoise,
    kLateral,
    kDropout,
    kFlying,
    kFlyingMix,
    kExposure,
    kTofNoise,
    kLostReturn,
    kEdgeDropout,
    kCorrelatedDisparity,
    kSmoothColorNoise,
    kFixedDisparity,
    kDisparityPattern
};

struct RenderedFrame {
    cv::Mat color;              // CV_8UC3, BGR, colour camera size
    cv::Mat depth;              // CV_32FC1 metres registered to the colour camera (colour size); 0 = no reading
    cv::Mat depth_native;       // CV_32FC1 metres as the depth camera measures it (its own size and pose)
    double mean_luminance = 0;  // of the colour image before exposure (linear), for the auto-exposure
};

class Renderer {
public:
    Renderer(const Scene& scene, const SensorModel& sensor, uint64_t seed);

    // Renders the frame whose colour camera pose (camera-to-world) is `pose`. `velocity_pose` is the
    // camera pose one frame interval later (or earlier, negated by the caller); with `blur` the colour
    // image integrates the motion over the exposure time (`frame_interval_s` apart from it).
    RenderedFrame render(uint64_t frame_index, const Eigen::Isometry3d& pose, const Eigen::Isometry3d& next_pose, double frame_interval_s,
                         bool blur) const;
    // The colour image at f.color_pose, the depth image at f.depth_pose (the colour camera's pose at
    // the depth stamp: the depth camera sits at depth_in_color from it).
    RenderedFrame render(uint64_t frame_index, const PlannedFrame& f, bool blur) const;

    const SensorModel& sensor() const { return sensor_; }

    // Every pixel's ray through the camera's distortion model (also what `synth stats --camera`
    // measures depth with, so a rendering is measured along the rays it was cast on).
    struct RayMap {
        int width = 0, height = 0;
        std::vector<Eigen::Vector3d> dirs;      // unit ray direction per pixel, camera frame
        std::vector<Eigen::Vector3d> on_plane;  // the same rays scaled to z = 1 (dirs / dirs.z())
    };
    static RayMap make_ray_map(const PinholeCamera& camera);

private:
    // The camera pose at which each image row is exposed: a rolling shutter reads row v out at
    // (v / rows − ½)·readout_s around the frame's stamp, while the camera moves from `pose` towards
    // `next_pose` (reached `interval_s` later). All rows share `pose` when readout_s is 0.
    static std::vector<Eigen::Isometry3d> row_poses(const Eigen::Isometry3d& pose, const Eigen::Isometry3d& next_pose, double interval_s,
                                                    double readout_s, int rows);

    void render_color(uint64_t frame, const PlannedFrame& f, bool blur, RenderedFrame& out) const;
    // One frame's per-pixel random streams of the depth effects, each mixed from (seed, salt, frame) once.
    struct DepthStreams {
        DepthStreams(uint64_t seed, uint64_t frame);
        HashStream lateral, lost_return, disparity, edge_dropout, dropout, tof, flying, flying_mix;
    };
    struct DepthRay {
        Hit hit;
        double z = 0;          // depth along the depth camera's optical axis
        double incidence = 0;  // angle between ray and surface normal, rad
    };
    // The rays of depth pixels u0 … u0 + n − 1 of row v (n ≤ RayIndex::kPacket), with lateral jitter,
    // traced as one packet; found[i] is false where ray i hits nothing.
    void cast_depth_rays(const DepthStreams& random, const Eigen::Isometry3d& depth_pose, int u0, int n, int v, DepthRay* out,
                         bool* found) const;
    // Whether the return of a depth ray is lost on the surface it hit (dark, glossy, glass; and for
    // Kinect v1 with range): blobs fixed on the surface, their edges flickering from frame to frame.
    bool return_lost(const DepthStreams& random, uint64_t pixel, const DepthRay& ray) const;
    void render_depth_structured_light(uint64_t frame, const PlannedFrame& f, RenderedFrame& out) const;
    void render_depth_time_of_flight(uint64_t frame, const PlannedFrame& f, RenderedFrame& out) const;
    // Kinect v1's fixed disparity pattern (effect disparity_pattern) on the depth grid, px: the same in
    // every frame, so it is made once.
    static cv::Mat make_disparity_pattern(const SensorModel& sensor, int width, int height, uint64_t seed);

    const Scene& scene_;
    SensorModel sensor_;
    uint64_t seed_;
    RayMap color_rays_, depth_rays_;
    std::optional<rgbd::DepthRegistration> registration_;  // time of flight: depth to colour, set up once
    cv::Mat disparity_pattern_;                            // structured light: CV_64F, px; empty: none
};

// The registration library's view of a camera.
rgbd::Intrinsics intrinsics_of(const PinholeCamera& camera);

}  // namespace vobench::synth
