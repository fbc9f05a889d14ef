// measured_path.hpp — a trajectory file is a measurement: the camera moved along a smooth path, and
// the file holds that path plus the motion capture's noise (effect `measured_reference`).
//
// Why it matters for a rendering: TUM's 100-Hz reference poses jitter from sample to sample by
// 0.02–0.07° per axis (fr1, fr2, fr3 alike). The jitter is the capture's noise, not the camera's
// motion: the second differences of successive orientations correlate at lag 1 by −0.2 to −0.58 per
// axis (white noise alone: −2/3; smooth motion: near +1). A rendering taken straight along the file moves
// its camera by that jitter — every frame's rolling shutter and motion blur then follow a velocity
// that changes by most of itself from one frame to the next (fr3/long_office at 33 Hz: a median step
// of 0.32° changes by 0.25° between frames), a shake no real Kinect has — while its reference is
// exact, unlike the real one. With the effect on, the camera is rendered along the file's smoothed
// path and the file's own poses stay the reference, noise and all, as a real recording has them.
//
// The smoothing, local and free of tuning: each pose is a Gaussian-weighted quadratic fit in time to
// its neighbours (position directly, orientation in the tangent space at the nearest sample); the
// width is the largest of a few whose residual stays within the noise read off the file itself (the
// discrepancy principle, Morozov 1966) — on TUM's fr1/rpy sample 15 ms: its noise is 0.060 / 0.031 /
// 0.024° (RMS 0.041°), the residual 0.034° at 15 ms and 0.043° at 20 ms.
#pragma once

#include "metrics/pose.hpp"

#include <Eigen/Core>

namespace vobench::synth {

// The white noise of a sampled trajectory, per axis: σ from the robust (median) third differences of
// its orientations (in the body frame) and positions, Var(Δ³x) = 20σ² for white noise on smooth
// motion. Runs of four samples whose intervals differ by more than 10 % are not used (a gap is no
// difference). On TUM's references the second differences give 2–10 % more: the noise dominates both.
struct PathNoise {
    Eigen::Vector3d rotation_rad = Eigen::Vector3d::Zero();
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
    std::size_t differences = 0;  // the third differences used
};
PathNoise estimate_path_noise(const metrics::Trajectory& poses);

// Each pose fitted to its neighbours within ±3 bandwidths (Gaussian weights of σ = bandwidth, a
// quadratic in time); a pose with fewer than five neighbours there is kept as it is. Stamps unchanged.
metrics::Trajectory smooth_path(const metrics::Trajectory& poses, double bandwidth_s);

// The measured path's smooth version and how it was found (synth.json records it).
struct MeasuredPath {
    metrics::Trajectory smooth;                                 // the path rendered
    PathNoise noise;                                            // read off the file
    double bandwidth_s = 0;                                     // 0: too few poses or no noise to remove; `smooth` is the input
    double residual_rotation_rad = 0, residual_position_m = 0;  // RMS over axes of input − smooth
};

// The widest bandwidth of 1, 1.5, 2, 3, 4, 6 and 8 median sampling intervals whose residual RMS stays
// within the estimated noise of the orientations (whose jitter is what moves an image); none when even
// the narrowest exceeds it.
MeasuredPath smooth_measured_path(const metrics::Trajectory& poses);

}  // namespace vobench::synth
