// frame_statistics.hpp — `vobench synth stats DIR…`: the image and depth statistics that decide how
// hard an RGB-D sequence is for visual odometry, measured the same way on any TUM-layout folder (real
// or rendered), so a rendering can be calibrated against real frames (issue #15) and anyone can check.
//
// Per associated colour–depth pair (TUM's association, < 20 ms), averaged over the frames:
//   missing depth: overall, in the 16-px image border, by brightness of the colour pixel, and by
//     range (a hole takes the range of the nearest valid depth within 8 px; holes with none are "far");
//   depth noise: the median residual RMS of plane fits z = a·u + b·v + c in 8×8 patches of complete
//     depth that are planar (residual < 2 % of z), by range band; the same in 32×32 patches, and how
//     the noise is shared between neighbours there (at 1.5–3 m: the residuals' correlation with those
//     1, 4 and 8 px to the right and 4 px below — a block matcher's window shares it over its width);
//   the depth histogram (share of valid pixels per 1 m band);
//   image noise: Immerkær's estimator (1996, "Fast noise variance estimation") on the grey image,
//     σ = √(π/2) / (6 (W−2)(H−2)) · Σ |I ∗ N|, N = [1 −2 1; −2 4 −2; 1 −2 1];
//   gradient density: share of pixels whose Sobel gradient magnitude exceeds 40 (grey levels · 4);
//   FAST corners per frame at threshold 20 with non-maximum suppression (put_vo's detector setting);
//   sharpness: the variance of the Laplacian (motion blur and defocus lower it), and the same divided
//     by the squared mean gradient (edge sharpness, independent of how much texture there is);
//   the grey image's variance by octave of wavelength (2–4 px up to 128–256 px) and its spectral
//     exponent α (image_spectrum.hpp: where contrast is missing, by scale);
//   brightness: mean grey level and the share of saturated pixels (≥ 250);
//   brightness change from the colour frame before (auto-exposure and gain; photometric_gain.hpp):
//     the median and 90th percentile over the frames of the |log ratio| of tracked corners' linear
//     brightness, in per cent; over consecutive frames, the auto-exposure time constant that best
//     explains the gains, the share of their variance it explains, how much the scene's own
//     brightness (observed mean over the summed gains) varies over the views, and its correlation
//     with the frames' median depth;
//   colour–depth stamp offset: mean and largest |t_rgb − t_depth| of the pairs, milliseconds;
//   registration: the shift (±4 px) of the depth-step map (centred steps over 10 % of z) that best
//     overlaps the colour-edge map (Sobel > 60), pooled over frames — depth–colour misregistration.
// With a camera model (`--camera`), also (depth_geometry.hpp): the ICP conditioning of each frame's
// depth, how much of the projector's shadow beside depth steps the depth shows as holes, and — when the folder has groundtruth.txt — the
// depth residual under the reference's motion at gaps of 1, 4 and 16 frames (how far the ground truth disagrees with the images).
#pragma once

#include "synth/sensor_model.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace vobench::synth {

struct Statistic {
    std::string key;    // stable identifier, e.g. "missing_depth.range_1_2m"
    std::string label;  // for the table
    double value = 0;   // mean over frames (NaN when no frame had a sample)
};

struct FolderStatistics {
    std::filesystem::path folder;
    std::size_t frames = 0;  // pairs measured
    std::vector<Statistic> values;
};

// Reads rgb.txt, depth.txt (16-bit PNG, `depth_scale` units per metre) and the images. At most
// `max_frames` pairs, evenly spaced (0: all). Throws std::runtime_error naming the file that cannot
// be read; a frame whose images cannot be decoded is an error too (a statistic must not silently
// skip data), and so is a groundtruth.txt that cannot be read (naming file:line). `camera`: the colour
// camera the depth is registered to, or null to leave out the statistics that need one.
FolderStatistics measure_folder(const std::filesystem::path& folder, std::size_t max_frames = 0, double depth_scale = 5000.0,
                                const PinholeCamera* camera = nullptr);

}  // namespace vobench::synth
