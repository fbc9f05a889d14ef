// libFuzzer target: the readers' PNG path (plugins/common/png_raster.cpp) on any bytes — a decoded image
// or "not here", never a crash, an overflow or a read past the buffer. Three ways in, by the first byte:
//   0: the bytes as a file;
//   1: the bytes as a file with every chunk's CRC made right, so mutations get past the CRC checks;
//   2: a header from bytes 1–4 and the rest as the inflated rows (filter bytes and samples, the right
//      length or not), compressed and wrapped here, so arbitrary filter types and sizes reach the
//      row filters (a mutated zlib stream would fail its Adler-32 before them).
// The seeds are small valid PNGs, so mutations start from the chunk walk's good path.
#include "png_raster.hpp"

#include <libdeflate.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<uint8_t>(v >> s));
}

void chunk(std::vector<uint8_t>& out, const char* type, const std::vector<uint8_t>& body) {
    put32(out, static_cast<uint32_t>(body.size()));
    const std::size_t typed = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), body.begin(), body.end());
    put32(out, libdeflate_crc32(0, out.data() + typed, body.size() + 4));
}

void fix_crcs(std::vector<uint8_t>& b) {
    for (std::size_t at = 8; at + 12 <= b.size();) {
        const uint32_t length = uint32_t{b[at]} << 24 | uint32_t{b[at + 1]} << 16 | uint32_t{b[at + 2]} << 8 | b[at + 3];
        if (length > b.size() - at - 12) return;
        const uint32_t crc = libdeflate_crc32(0, b.data() + at + 4, std::size_t{length} + 4);
        for (int k = 0; k < 4; ++k) b[at + 8 + length + k] = static_cast<uint8_t>(crc >> (24 - 8 * k));
        at += std::size_t{length} + 12;
    }
}

std::vector<uint8_t> wrapped(const uint8_t* data, std::size_t size) {
    if (size < 5) return {};
    const uint32_t width = 1 + data[1] % 64, height = 1 + data[2] % 64;
    static const uint8_t kinds[][2] = {{8, 0}, {8, 2}, {8, 4}, {8, 6}, {16, 0}, {16, 2}, {8, 3}};  // bit depth, colour type
    const uint8_t* kind = kinds[data[3] % 7];
    const std::vector<uint8_t> rows(data + 5, data + size);
    libdeflate_compressor* c = libdeflate_alloc_compressor(1);
    std::vector<uint8_t> z(libdeflate_zlib_compress_bound(c, rows.size()));
    z.resize(libdeflate_zlib_compress(c, rows.data(), rows.size(), z.data(), z.size()));
    libdeflate_free_compressor(c);
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'}, header;
    put32(header, width);
    put32(header, height);
    header.insert(header.end(), {kind[0], kind[1], 0, 0, static_cast<uint8_t>(data[4] & 1)});  // sometimes interlaced
    chunk(png, "IHDR", header);
    chunk(png, "IDAT", z);
    chunk(png, "IEND", {});
    return png;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    std::vector<uint8_t> bytes;
    switch (data[0] % 3) {
        case 0: bytes.assign(data + 1, data + size); break;
        case 1:
            bytes.assign(data + 1, data + size);
            fix_crcs(bytes);
            break;
        default: bytes = wrapped(data, size); break;
    }
    const auto raster = vobench::files::decode_png_raster(bytes.data(), bytes.size());
    if (raster && (raster->pixels.size() != raster->stride * raster->height || raster->width == 0)) __builtin_trap();
    return 0;
}
