// png_decode.hpp — PNG decoding for the frame path of the dataset readers, as cv::Mat.
//
// Why not cv::imread alone: a Kinect v2 frame is a 1920×1080 colour PNG plus a depth PNG, and reading
// them was most of a Kinect v2 cell's time (issue #19). png_raster.hpp inflates with libdeflate, about
// twice as fast as the zlib inside libpng; the pixels are identical (tested against cv::imread). Only
// the common cases take this path — 8-bit grey/RGB/RGBA (± alpha) as BGR colour, 16-bit grey as depth —
// and everything else falls back to cv::imread, so what a file decodes to never depends on the path.
#pragma once

#include <opencv2/core.hpp>

#include <filesystem>

namespace vobench::files {

// The decoded image as cv::imread(path, imread_flags) would give it (IMREAD_COLOR: 8-bit BGR;
// IMREAD_UNCHANGED: a 16-bit grey PNG as CV_16UC1), or an empty matrix when the file is not a plain
// PNG of those kinds, broken ones included (the caller then uses cv::imread, whose verdict stands).
// Throws sdk::Error(VOBENCH_IO_ERROR) naming the file only when it cannot be read at all.
cv::Mat decode_png(const std::filesystem::path& path, int imread_flags);

}  // namespace vobench::files
