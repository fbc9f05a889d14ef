#include "png_decode.hpp"

#include "dataset_files.hpp"
#include "png_raster.hpp"

#include <vobench/plugin.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <optional>
#include <string>
#include <vector>

namespace vobench::files {

cv::Mat decode_png(const std::filesystem::path& path, int imread_flags) {
    const std::string file = read_text(path);  // opened in binary mode: the bytes as they are
    const auto* bytes = reinterpret_cast<const uint8_t*>(file.data());
    // Bytes 24 and 25 are IHDR's bit depth and colour type: kinds this path does not convert are not inflated.
    if (file.size() < 26) return {};
    const int bit_depth = bytes[24], color_type = bytes[25];
    const bool colour = imread_flags == cv::IMREAD_COLOR && bit_depth == 8 && color_type != 3;
    const bool depth16 = imread_flags == cv::IMREAD_UNCHANGED && bit_depth == 16 && color_type == 0;
    if (!colour && !depth16) return {};
    const std::optional<PngRaster> raster = decode_png_raster(bytes, file.size());
    if (!raster) return {};
    const PngRaster& r = *raster;
    const int rows = static_cast<int>(r.height), cols = static_cast<int>(r.width);
    uint8_t* first = const_cast<uint8_t*>(r.pixels.data()) + 1;  // past row 0's filter byte
    if (imread_flags == cv::IMREAD_COLOR && r.bit_depth == 8) {
        static const int codes[] = {0, cv::COLOR_GRAY2BGR, 0, cv::COLOR_RGB2BGR, cv::COLOR_RGBA2BGR};
        cv::Mat bgr;
        if (r.channels == 2) {  // grey + alpha: the grey, as libpng's strip-alpha gives it
            cv::Mat grey(rows, cols, CV_8UC1);
            const int from_to[] = {0, 0};
            cv::mixChannels(std::vector<cv::Mat>{cv::Mat(rows, cols, CV_8UC2, first, r.stride)}, std::vector<cv::Mat>{grey}, from_to, 1);
            cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
        } else {
            cv::cvtColor(cv::Mat(rows, cols, CV_8UC(r.channels), first, r.stride), bgr, codes[r.channels]);
        }
        return bgr;
    }
    if (imread_flags == cv::IMREAD_UNCHANGED && r.bit_depth == 16 && r.channels == 1) {
        cv::Mat depth(rows, cols, CV_16UC1);
        for (int y = 0; y < rows; ++y) {
            const uint8_t* in = first + static_cast<std::size_t>(y) * r.stride;
            uint16_t* out = depth.ptr<uint16_t>(y);
            for (int x = 0; x < cols; ++x) out[x] = static_cast<uint16_t>(in[2 * x] << 8 | in[2 * x + 1]);  // big-endian samples
        }
        return depth;
    }
    return {};  // a kind cv::imread converts in its own ways: left to it
}

}  // namespace vobench::files
