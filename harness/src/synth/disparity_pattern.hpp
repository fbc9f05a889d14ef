// disparity_pattern.hpp — a Kinect v1 unit's fixed disparity error beyond its low-order field (issue #15;
// `vobench synth stats --camera`, rows "fixed disparity pattern").
//
// Why it matters: a structured-light unit's disparity carries a fixed error δ(u, v) that stays with the
// camera, not the scene (Smisek et al. 2011 show its residual pattern; Herrera et al. 2012 calibrate it
// per pixel). Its low-order part a·r² + b·x + c·y is what disparity_distortion_fit.hpp measures. On the
// real fr1/rpy depth what is left after that still varies over the image in blobs of about a hundred
// pixels by ±0.1–0.3 px — centimetres at 3 m. A turning camera carries every surface point across those
// blobs, so the error they put into the motion follows the turn from frame to frame instead of
// averaging out (depth-only ICP turns by it).
//
// How, from the depth images and the reference alone: for the pairs (i, i + 4) and (i, i + 8), frame i's
// depth (every 2nd pixel) moved by the reference's motion (poses at the clock ticks less the depth
// latency, as disparity_distortion_fit.hpp) lands at pixel q of frame j, where the disparity residual
// r = f·b·(1 / z_j(q) − 1 / z) is δ(q) − δ(p) plus noise (p its pixel in frame i; residuals over 5 % of z
// are occlusions and over 1 px mismatches, both dropped). δ on a lattice of 16-px cells (of a 640-wide
// image) is the least-squares solution of all those differences, with a weak smoothness term between
// neighbouring cells and its mean held at 0; cells seen fewer than 50 times stay unknown. The best
// a·r² + b·x + c·y + constant over the cells is taken off: the rest is the pattern.
#pragma once

#include "synth/depth_geometry.hpp"
#include "synth/disparity_distortion_fit.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <limits>

namespace vobench::synth {

struct DisparityPattern {
    static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
    double rms_px = kUnknown;              // the pattern's RMS over the known cells, px of disparity
    double halves_correlation = kUnknown;  // between the patterns solved from the first and the second half of
                                           // the frames: a fixed pattern repeats, noise and the scene's errors do not
    double correlation_64px = kUnknown;    // the pattern's correlation with itself 64 px away (of a 640-wide
                                           // image; mean of along and across the rows): how large its blobs are
    std::size_t pairs = 0;                 // frame pairs the reference covers
    int cell_px = 0;                       // the lattice's cell size in the image's pixels
    Eigen::MatrixXd cells;                 // the pattern from all pairs, rows × columns of cells; NaN: unknown
};

// All figures NaN (and `cells` empty) when either half of the frames has fewer than 10 covered pairs:
// too short a sequence to tell a fixed pattern from noise. `focal_baseline_px_m` converts depth to
// disparity (f·b of the IR camera, DistortionFitOptions' default for a Kinect v1).
DisparityPattern estimate_disparity_pattern(const DepthSequence& sequence, const DepthRays& rays, double depth_latency_s,
                                            double focal_baseline_px_m);

}  // namespace vobench::synth
