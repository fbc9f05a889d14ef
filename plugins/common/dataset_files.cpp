#include "dataset_files.hpp"

#include "png_decode.hpp"

#include <vobench/plugin.hpp>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <future>
#include <sstream>
#include <system_error>

namespace vobench::files {

using sdk::Error;

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(VOBENCH_IO_ERROR, path.string() + ": cannot open file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

cv::Mat load_image(const std::filesystem::path& path, int flags) {
    if (!std::filesystem::exists(path)) throw Error(VOBENCH_IO_ERROR, path.string() + ": missing file");
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    cv::Mat m;
    if (extension == ".png") m = decode_png(path, flags);  // empty: not a plain PNG of the kinds it decodes
    if (!m.empty()) return m;
    try {
        m = cv::imread(path.string(), flags);
    } catch (const cv::Exception& e) {
        throw Error(VOBENCH_IO_ERROR, path.string() + ": cannot decode image (" + e.what() + ")");
    }
    if (m.empty()) throw Error(VOBENCH_IO_ERROR, path.string() + ": cannot decode image (corrupt or truncated?)");
    return m;
}

ColorAndDepth load_color_and_depth(const std::filesystem::path& color, int color_flags, const std::filesystem::path& depth,
                                   int depth_flags) {
    std::future<cv::Mat> depth_image;
    try {
        depth_image = std::async(std::launch::async, [&] { return load_image(depth, depth_flags); });
    } catch (const std::system_error&) {  // no thread to be had (a process limit): one after the other
        return {load_image(color, color_flags), load_image(depth, depth_flags)};
    }
    cv::Mat color_image = load_image(color, color_flags);  // if this throws, the future's destructor waits
    return {std::move(color_image), depth_image.get()};
}

void require_depth16(const cv::Mat& depth, const std::filesystem::path& path) {
    if (depth.type() != CV_16UC1)
        throw Error(VOBENCH_IO_ERROR, path.string() + ": depth must be a 16-bit single-channel PNG, found " +
                                          (depth.depth() == CV_8U ? "8-bit" : "another type"));
}

void require_frame_index(uint64_t index, std::size_t count) {
    if (index >= count)
        throw Error(VOBENCH_OUT_OF_RANGE, "frame " + std::to_string(index) + " is past the end (" + std::to_string(count) + " frames)");
}

void declare_gt_accuracy(vobench_sequence_info& info, const std::filesystem::path& sequence) {
    const bool rendered = std::filesystem::exists(sequence / "synth.json");
    info.gt_position_sigma_m = info.gt_rotation_sigma_deg = rendered ? 0.0 : -1.0;
}

vobench_image image_of(const cv::Mat& m, vobench_pixel_format format) {
    return {sizeof(vobench_image), m.cols, m.rows, static_cast<int32_t>(m.step[0]), format, m.data};
}

}  // namespace vobench::files
