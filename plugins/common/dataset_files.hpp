// dataset_files.hpp — what every dataset reader does with files: read a text file, decode an image,
// check a depth image's type, and describe a cv::Mat as an ABI image. Failures are
// vobench::sdk::Error(VOBENCH_IO_ERROR) naming the file.
#pragma once

#include <vobench/vobench_plugin.h>
#include <vobench/plugin.hpp>

#include <opencv2/core.hpp>

#include <filesystem>
#include <string>

namespace vobench::files {

std::string read_text(const std::filesystem::path& path);

// cv::imread with clear messages: "missing file", "cannot decode image (corrupt or truncated?)";
// plain PNGs of the usual kinds inflated with libdeflate instead (png_decode.hpp), with the same pixels.
cv::Mat load_image(const std::filesystem::path& path, int imread_flags);

// One frame's colour and depth images, decoded at the same time on two threads: for Kinect v2 each is a
// PNG that takes tens of milliseconds (issue #19). Errors as load_image's; colour's first if both fail.
struct ColorAndDepth {
    cv::Mat color, depth;
};
ColorAndDepth load_color_and_depth(const std::filesystem::path& color, int color_flags, const std::filesystem::path& depth,
                                   int depth_flags);

// Throws unless `depth` is 16-bit single-channel ("found 8-bit" when it is 8-bit).
void require_depth16(const cv::Mat& depth, const std::filesystem::path& path);

// Throws VOBENCH_OUT_OF_RANGE "frame I is past the end (N frames)" unless index < count.
void require_frame_index(uint64_t index, std::size_t count);

// The ground truth's declared accuracy (API 2) for a reader whose data comes with no published figure:
// exact (0) when vobench rendered the sequence (synth.json in `sequence`), else not known (-1).
void declare_gt_accuracy(vobench_sequence_info& info, const std::filesystem::path& sequence);

// The ABI view of a matrix; valid as long as `m` keeps its pixels.
vobench_image image_of(const cv::Mat& m, vobench_pixel_format format);

// Runs a parser, turning its std::runtime_error (a message naming file and line) into an I/O error.
template <typename F>
auto parsed(F&& parse) {
    try {
        return parse();
    } catch (const sdk::Error&) {
        throw;
    } catch (const std::runtime_error& e) {
        throw sdk::Error(VOBENCH_IO_ERROR, e.what());
    }
}

}  // namespace vobench::files
