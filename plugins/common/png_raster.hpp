// png_raster.hpp — the pixels of a plain PNG file in memory, inflated with libdeflate.
//
// Why not libpng (inside cv::imread) or libspng: both inflate with zlib, and for a Kinect v2 frame
// (1920×1080 colour, 1920×1080 or 512×424 16-bit depth) inflating is most of the reading time. Measured
// on a rendered Kinect v2 colour frame: zlib 20.7 ms, libdeflate 10.2 ms; libspng decodes the frame in
// the same 36 ms as cv::imread (issue #19). libdeflate does the inflating and its checksums; this file
// only walks the chunks (PNG spec, W3C 2003, §5) and undoes the row filters (§9).
//
// Only the plain cases are decoded: non-interlaced, 8-bit grey/grey+alpha/RGB/RGBA or 16-bit grey,
// no palette or transparency chunk, every CRC and the zlib checksum right, exactly the image's bytes in
// the stream. For anything else the answer is "not here" and the caller falls back to cv::imread,
// which then decodes the file or says why not: this path never accepts a file that libpng refuses.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace vobench::files {

struct PngRaster {
    uint32_t width = 0, height = 0;
    int bit_depth = 8;  // 8, or 16 (grey only)
    int channels = 1;   // 1 grey, 2 grey+alpha, 3 RGB, 4 RGBA
    // Row y's samples start at pixels[y * stride + 1] (byte 0 of each row held its filter type);
    // 16-bit samples are big-endian, as in the file.
    std::size_t stride = 0;
    std::vector<uint8_t> pixels;
};

// The image of a PNG file's bytes, or nullopt when this is not a plain PNG this path decodes.
// 2^26 pixels at most (8192×8192): beyond that cv::imread's own limits decide.
std::optional<PngRaster> decode_png_raster(const uint8_t* data, std::size_t size);

}  // namespace vobench::files
