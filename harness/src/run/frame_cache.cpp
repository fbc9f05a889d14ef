#include "run/frame_cache.hpp"

#include "metrics/trajectory_io.hpp"

#include <fmt/format.h>
#include <zstd.h>

#include <cstring>
#include <fstream>
#include <sstream>

namespace vobench {
namespace fs = std::filesystem;

namespace {

// A 64-bit hash over bytes, 8 at a time (multiply–xorshift, as in MurmurHash's finaliser): fast enough
// to hash a whole sequence, which costs less than decoding it once.
class Hasher {
public:
    void add(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (; size >= 8; p += 8, size -= 8) {
            uint64_t w;
            std::memcpy(&w, p, 8);
            mix(w);
        }
        uint64_t tail = 0;
        std::memcpy(&tail, p, size);
        mix(tail ^ (static_cast<uint64_t>(size) << 56));
    }
    void add(const std::string& s) { add(s.data(), s.size()); }
    uint64_t value() const { return h_; }

private:
    void mix(uint64_t w) {
        w *= 0x87c37b91114253d5ull;
        w ^= w >> 31;
        h_ = (h_ ^ w) * 0x9e3779b97f4a7c15ull;
        h_ ^= h_ >> 29;
    }
    uint64_t h_ = 0x6a09e667f3bcc908ull;
};

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
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(sequence))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    std::vector<char> buffer(1 << 20);
    for (const fs::path& f : files) {
        h.add(fs::relative(f, sequence).generic_string());
        std::ifstream in(f, std::ios::binary);
        while (in) {
            in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
            h.add(buffer.data(), static_cast<std::size_t>(in.gcount()));
        }
    }
    return fmt::format("{:016x}", h.value());
}

FrameCache::FrameCache(fs::path folder) : folder_(std::move(folder)) { fs::create_directories(folder_); }

fs::path FrameCache::file_of(uint64_t index) const { return folder_ / fmt::format("frame_{:06d}.vbf", index); }

bool FrameCache::complete() const { return fs::exists(folder_ / "complete"); }

void FrameCache::mark_complete(uint64_t frames) const {
    metrics::write_file_atomic(folder_ / "complete", fmt::format("{} frames\n", frames));
}

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
    metrics::write_file_atomic(file_of(index), text);
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
