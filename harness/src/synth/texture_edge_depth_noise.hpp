// texture_edge_depth_noise.hpp — is a frame's depth noisier where the image has texture edges?
// (issue #15; a `synth stats` statistic.)
//
// A structured-light Kinect finds disparity by correlating a window of its speckle pattern; where the
// surface's reflectance changes inside that window (printed text, a poster's edge) the speckles'
// brightness changes with it and the match can shift, so a flat but textured surface can measure
// noisier at its texture edges than between them. Feature-based odometry takes the depth of its points
// exactly there. The statistic: in 24×24 patches whose depth is complete and planar (a plane fit in
// pixel coordinates leaves an RMS under 1 % of the depth — no geometric edge inside), the mean
// |residual| / z at pixels on grey-level edges (3×3 Sobel magnitude > 40) divided by that at pixels
// away from them (< 10), both pooled over the frame's patches. 1: no dependence. Measured on TUM's
// fr1/rpy and fr1/desk samples and renderings (docs/synthetic-sensors.md).
#pragma once

#include <opencv2/core.hpp>

#include <optional>

namespace vobench::synth {

// The least-squares plane z = c + a·(x − centre) + b·(y − centre) over a complete patch×patch square
// at (x, y) of `depth_m` (metres, CV_32FC1) and its RMS residual (3 degrees of freedom taken); empty
// when a pixel of the square has no depth.
struct PatchPlane {
    double a = 0, b = 0, c = 0, rms = 0;
    double at(int i, int j, int patch) const { return c + a * (i - (patch - 1) / 2.0) + b * (j - (patch - 1) / 2.0); }
};
std::optional<PatchPlane> fit_patch_plane(const cv::Mat& depth_m, int x, int y, int patch);

// The frame's ratio (above); empty when fewer than 200 pixels fall on either side.
// `grey` is CV_8UC1 of the depth's size.
std::optional<double> texture_edge_depth_noise_ratio(const cv::Mat& depth_m, const cv::Mat& grey);

}  // namespace vobench::synth
