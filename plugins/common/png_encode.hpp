// png_encode.hpp — PNG encoding for the frames `vobench synth` writes, deflated with libdeflate.
//
// Why not cv::imwrite: libpng tries all five row filters on every row to pick one, and deflates with
// zlib; for a rendered Kinect v2 frame that was ~190 ms of colour and ~70 ms of depth, on the same two
// cores that render the next frame (issue #15, item 7). Here each row gets one filter chosen for the
// image's kind (below), and libdeflate compresses the whole stream at once, several times faster
// than zlib at the same level. The file is a plain PNG (W3C 2003): what any decoder reads back is the
// image's exact pixels (tested against cv::imread).
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace vobench::files {

// The PNG file of `image`: CV_8UC3 (BGR, stored as RGB), CV_8UC1 (grey) or CV_16UC1 (16-bit grey, as
// TUM and PUTK² store depth). `level` is libdeflate's (1 fastest … 12 smallest). Throws
// std::invalid_argument for another type or an empty image.
std::vector<uint8_t> encode_png(const cv::Mat& image, int level = 1);

// encode_png written to `path` (replacing it); throws std::runtime_error naming the path when it
// cannot be written.
void write_png(const std::filesystem::path& path, const cv::Mat& image, int level = 1);

}  // namespace vobench::files
