#include "png_raster.hpp"

#include <libdeflate.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

namespace vobench::files {
namespace {

uint32_t be32(const uint8_t* p) { return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | p[3]; }

struct DecompressorFree {
    void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

// PNG spec §9.4: the Paeth predictor.
inline int paeth(int a, int b, int c) {
    const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
    return pa <= pb && pa <= pc ? a : (pb <= pc ? b : c);
}

// Undoes one row's filter in place (§9.2). `prior`: the row above, already unfiltered, or null for
// the first row (all zero, so Up is nothing, Average halves the left byte, Paeth is Sub). BPP, the
// bytes per pixel, is a template argument for the common sizes: each byte depends on the one BPP
// before it, and a constant distance lets the compiler keep the chain in registers.
template <std::size_t BPP>
bool unfilter_fixed(uint8_t type, uint8_t* row, const uint8_t* prior, std::size_t n, std::size_t bpp_runtime) {
    const std::size_t bpp = BPP ? BPP : bpp_runtime;
    switch (type) {
        case 0: return true;
        case 1:
            for (std::size_t x = bpp; x < n; ++x) row[x] = static_cast<uint8_t>(row[x] + row[x - bpp]);
            return true;
        case 2:
            if (prior)
                for (std::size_t x = 0; x < n; ++x) row[x] = static_cast<uint8_t>(row[x] + prior[x]);
            return true;
        case 3:
            if (prior) {
                for (std::size_t x = 0; x < bpp && x < n; ++x) row[x] = static_cast<uint8_t>(row[x] + (prior[x] >> 1));
                for (std::size_t x = bpp; x < n; ++x) row[x] = static_cast<uint8_t>(row[x] + ((row[x - bpp] + prior[x]) >> 1));
            } else {
                for (std::size_t x = bpp; x < n; ++x) row[x] = static_cast<uint8_t>(row[x] + (row[x - bpp] >> 1));
            }
            return true;
        case 4:
            if (!prior) return unfilter_fixed<BPP>(1, row, nullptr, n, bpp);
            for (std::size_t x = 0; x < bpp && x < n; ++x) row[x] = static_cast<uint8_t>(row[x] + prior[x]);
            for (std::size_t x = bpp; x < n; ++x) row[x] = static_cast<uint8_t>(row[x] + paeth(row[x - bpp], prior[x], prior[x - bpp]));
            return true;
        default: return false;  // no such filter: a broken file
    }
}

bool unfilter(uint8_t type, uint8_t* row, const uint8_t* prior, std::size_t n, std::size_t bpp) {
    switch (bpp) {
        case 1: return unfilter_fixed<1>(type, row, prior, n, bpp);
        case 2: return unfilter_fixed<2>(type, row, prior, n, bpp);
        case 3: return unfilter_fixed<3>(type, row, prior, n, bpp);
        case 4: return unfilter_fixed<4>(type, row, prior, n, bpp);
        default: return unfilter_fixed<0>(type, row, prior, n, bpp);
    }
}

}  // namespace

std::optional<PngRaster> decode_png_raster(const uint8_t* data, std::size_t size) {
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 8 + 25 || std::memcmp(data, signature, 8) != 0) return std::nullopt;

    PngRaster r;
    std::string idat;  // the zlib stream, gathered from the IDAT chunks
    bool have_header = false, have_end = false, idat_done = false;
    for (std::size_t at = 8; at < size && !have_end;) {
        if (size - at < 12) return std::nullopt;  // truncated chunk
        const uint32_t length = be32(data + at);
        if (length > 0x7fffffffu || length > size - at - 12) return std::nullopt;
        const uint8_t* type = data + at + 4;
        const uint8_t* body = type + 4;
        if (libdeflate_crc32(0, type, length + 4) != be32(body + length)) return std::nullopt;
        const std::string name(reinterpret_cast<const char*>(type), 4);
        if (!have_header) {
            if (name != "IHDR" || length != 13) return std::nullopt;
            r.width = be32(body);
            r.height = be32(body + 4);
            r.bit_depth = body[8];
            const int color_type = body[9];
            // compression 0, filter method 0, no interlacing.
            if (body[10] != 0 || body[11] != 0 || body[12] != 0) return std::nullopt;
            if (color_type == 0 && (r.bit_depth == 8 || r.bit_depth == 16))
                r.channels = 1;
            else if (r.bit_depth != 8)
                return std::nullopt;
            else if (color_type == 2)
                r.channels = 3;
            else if (color_type == 4)
                r.channels = 2;
            else if (color_type == 6)
                r.channels = 4;
            else
                return std::nullopt;  // palette, or not a PNG colour type
            if (r.width == 0 || r.height == 0 || uint64_t{r.width} * r.height > (uint64_t{1} << 26)) return std::nullopt;
            have_header = true;
        } else if (name == "IDAT") {
            if (idat_done) return std::nullopt;  // IDAT chunks must be consecutive
            idat.append(reinterpret_cast<const char*>(body), length);
        } else {
            if (!idat.empty()) idat_done = true;
            if (name == "IEND") have_end = true;
            // A palette or transparency changes what cv::imread returns; any other critical chunk
            // (upper-case first letter) is one libpng would refuse: leave both to it.
            else if (name == "PLTE" || name == "tRNS" || (type[0] & 0x20) == 0)
                return std::nullopt;
        }
        at += std::size_t{length} + 12;
    }
    if (!have_end || idat.empty()) return std::nullopt;

    const std::size_t bpp = static_cast<std::size_t>(r.channels) * (r.bit_depth / 8);
    const std::size_t row_bytes = bpp * r.width;
    r.stride = row_bytes + 1;
    // Deflate cannot expand more than 1032:1 (RFC 1951: a 258-byte match per code of at least 2 bits),
    // so a small file claiming a large image is refused before its pixels are allocated.
    if (r.stride * r.height / 1032 > idat.size() + 64) return std::nullopt;
    r.pixels.resize(r.stride * r.height);
    static thread_local std::unique_ptr<libdeflate_decompressor, DecompressorFree> inflater(libdeflate_alloc_decompressor());
    if (!inflater) return std::nullopt;
    // Exactly the image's bytes, and a right Adler-32, or not at all (libdeflate checks both).
    if (libdeflate_zlib_decompress(inflater.get(), idat.data(), idat.size(), r.pixels.data(), r.pixels.size(), nullptr) !=
        LIBDEFLATE_SUCCESS)
        return std::nullopt;
    for (uint32_t y = 0; y < r.height; ++y) {
        uint8_t* row = r.pixels.data() + y * r.stride;
        if (!unfilter(row[0], row + 1, y == 0 ? nullptr : row + 1 - r.stride, row_bytes, bpp)) return std::nullopt;
    }
    return r;
}

}  // namespace vobench::files
