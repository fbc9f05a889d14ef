#include "track/frame_cache.hpp"

#include "metrics/trajectory_io.hpp"
#include "util/files.hpp"
#include "util/hash.hpp"

#include <fmt/format.h>
#include <zstd.h>

#include <cstring>
#include <fstream>
#include <sstream>

namespace vobench {
namespace fs = std::filesystem;

namespace {

struct ImageHeader {
    int32_t width, height, stride, format;
};

struct FrameHeader {
    char magic[8];  // "VBFRAME1"
    uint64_t index;
    double timestamp, depth_timestamp, depth_scale;
    ImageHeader color, depth;
    uint64_t color_bytes, depth_bytes, compressed_bytes;
};

constexpr char kMagic[8] = {'V', 'B', 'F', 'R', 'A', 'M', 'E', '1'};

}  // namespace

std::string sequence_key(const PluginLibrary& reader, const ParamMap& options, const fs::path& sequence) {
    Hasher h;
    h.add(reader.name());
    h.add(std::string(reader.descriptor().version));
    for (const auto& [k, v] : options) h.add(k + "=" + v);
    hash_tree(h, sequence);
    return fmt::format("{:016x}", h.value());
}

FrameCache::FrameCache(fs::path folder) : folder_(std::move(folder)) { fs::create_directories(folder_); }

fs::path FrameCache::file_of(uint64_t index) const { return folder_ / fmt::format("frame_{:06d}.vbf", index); }

bool FrameCache::complete() const { return fs::exists(folder_ / "complete"); }

void FrameCache::mark_complete(uint64_t frames) const { write_file_atomic(folder_ / "complete", fmt::format("{} frames\n", frames)); }

void FrameCache::store(uint64_t index, const vobench_frame& f) const {
    FrameHeader h{};
    std::memcpy(h.magic, kMagic, 8);
    h.index = index;
    h.timestamp = f.timestamp;
    h.depth_timestamp = f.depth_timestamp;
    h.depth_scale = f.depth_scale;
    h.color = {f.color->width, f.color->height, f.color->stride_bytes, f.color->format};
    h.depth = {f.depth->width, f.depth->height, f.depth->stride_bytes, f.depth->format};
    h.color_bytes = static_cast<uint64_t>(f.color->stride_bytes) * static_cast<uint64_t>(f.color->height);
    h.depth_bytes = static_cast<uint64_t>(f.depth->stride_bytes) * static_cast<uint64_t>(f.depth->height);
    std::string raw(h.color_bytes + h.depth_bytes, '\0');
    std::memcpy(raw.data(), f.color->data, h.color_bytes);
    std::memcpy(raw.data() + h.color_bytes, f.depth->data, h.depth_bytes);
    std::string packed(ZSTD_compressBound(raw.size()), '\0');
    const std::size_t n = ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), 1);
    if (ZSTD_isError(n)) throw std::runtime_error(file_of(index).string() + ": zstd: " + ZSTD_getErrorName(n));
    h.compressed_bytes = n;
    std::string text(reinterpret_cast<const char*>(&h), sizeof(h));
    text.append(packed.data(), n);
    write_file_atomic(file_of(index), text);
}

std::unique_ptr<OwnedFrame> FrameCache::load(uint64_t index) const {
    const fs::path path = file_of(index);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path.string() + ": missing from the frame cache");
    FrameHeader h;
    in.read(reinterpret_cast<char*>(&h), sizeof(h));
    if (!in || std::memcmp(h.magic, kMagic, 8) != 0 || h.index != index)
        throw std::runtime_error(path.string() + ": not a vobench cached frame (or of another frame)");
    std::string packed(h.compressed_bytes, '\0');
    in.read(packed.data(), static_cast<std::streamsize>(packed.size()));
    if (!in) throw std::runtime_error(path.string() + ": truncated");
    std::string raw(h.color_bytes + h.depth_bytes, '\0');
    const std::size_t n = ZSTD_decompress(raw.data(), raw.size(), packed.data(), packed.size());
    if (ZSTD_isError(n) || n != raw.size()) throw std::runtime_error(path.string() + ": corrupt (zstd)");
    vobench_image color{sizeof(vobench_image), h.color.width, h.color.height, h.color.stride, h.color.format, raw.data()};
    vobench_image depth{sizeof(vobench_image), h.depth.width, h.depth.height, h.depth.stride, h.depth.format, raw.data() + h.color_bytes};
    const vobench_frame f{sizeof(vobench_frame), index, h.timestamp, h.depth_timestamp, &color, &depth, h.depth_scale};
    return std::make_unique<OwnedFrame>(f);  // copies out of `raw`
}

}  // namespace vobench
