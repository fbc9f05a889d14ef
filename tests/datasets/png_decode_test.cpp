// The readers' PNG path (libdeflate, plugins/common/png_raster.cpp) against cv::imread: the same pixels
// for every kind of PNG it takes, cv::imread's result for the kinds it leaves, and clear errors
// naming the file for broken ones — on generated images and on the real TUM frames.
#include "png_decode.hpp"     // plugins/common
#include "dataset_files.hpp"  // plugins/common
#include "png_raster.hpp"     // plugins/common
#include "test_support.hpp"

#include <libdeflate.h>

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cstring>
#include <fstream>
#include <random>

using namespace vobench;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// Noise over a gradient: every byte value, and rows that PNG's filters code differently.
cv::Mat test_image(int type, uint32_t seed) {
    cv::Mat m(97, 131, type);
    cv::theRNG().state = seed;
    cv::randu(m, cv::Scalar::all(0), cv::Scalar::all(CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256));
    for (int y = 0; y < m.rows / 2; ++y) m.row(y).setTo(cv::Scalar::all(y * (CV_MAT_DEPTH(type) == CV_16U ? 1000 : 5)));
    return m;
}

void require_same(const cv::Mat& a, const cv::Mat& b) {
    REQUIRE(a.type() == b.type());
    REQUIRE(a.size() == b.size());
    CHECK(cv::norm(a, b, cv::NORM_INF) == 0);
}

std::string bytes_of(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

std::string error_of(const fs::path& p, int flags) {
    try {
        files::load_image(p, flags);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

// A PNG written here, not by libpng: every row filtered with the given type (PNG spec §9.2), so each
// filter, on the first row and the others, for 1 to 4 bytes a pixel, is undone by the decoder.
struct HandPng {
    int width, height, channels, bit_depth;
    std::vector<uint8_t> raw;  // unfiltered samples, rows one after another (16-bit: big-endian)
};

void put32(std::string& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>(v >> s & 0xff));
}

void chunk(std::string& out, const char* type, const std::string& body) {
    put32(out, static_cast<uint32_t>(body.size()));
    const std::string typed = type + body;
    out += typed;
    put32(out, libdeflate_crc32(0, typed.data(), typed.size()));
}

std::string encode(const HandPng& png, const std::vector<int>& filters) {
    const int bpp = png.channels * png.bit_depth / 8;
    const std::size_t row_bytes = static_cast<std::size_t>(png.width) * bpp;
    std::vector<uint8_t> filtered;
    for (int y = 0; y < png.height; ++y) {
        const uint8_t* row = png.raw.data() + y * row_bytes;
        const uint8_t* prior = y > 0 ? row - row_bytes : nullptr;
        const int type = filters[static_cast<std::size_t>(y) % filters.size()];
        filtered.push_back(static_cast<uint8_t>(type));
        for (std::size_t x = 0; x < row_bytes; ++x) {
            const int a = x >= static_cast<std::size_t>(bpp) ? row[x - bpp] : 0, b = prior ? prior[x] : 0,
                      c = prior && x >= static_cast<std::size_t>(bpp) ? prior[x - bpp] : 0;
            const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
            const int predictor[] = {0, a, b, (a + b) / 2, pa <= pb && pa <= pc ? a : (pb <= pc ? b : c)};
            filtered.push_back(static_cast<uint8_t>(row[x] - predictor[type]));
        }
    }
    libdeflate_compressor* compressor = libdeflate_alloc_compressor(6);
    std::vector<uint8_t> z(libdeflate_zlib_compress_bound(compressor, filtered.size()));
    z.resize(libdeflate_zlib_compress(compressor, filtered.data(), filtered.size(), z.data(), z.size()));
    libdeflate_free_compressor(compressor);
    std::string out("\x89PNG\r\n\x1a\n", 8), header;
    put32(header, static_cast<uint32_t>(png.width));
    put32(header, static_cast<uint32_t>(png.height));
    const int color_type[] = {0, 0, 4, 2, 6};
    header += {static_cast<char>(png.bit_depth), static_cast<char>(color_type[png.channels]), 0, 0, 0};
    chunk(out, "IHDR", header);
    const std::string stream(z.begin(), z.end());
    chunk(out, "IDAT", stream.substr(0, stream.size() / 2));  // two IDAT chunks: the stream is split anywhere
    chunk(out, "IDAT", stream.substr(stream.size() / 2));
    chunk(out, "IEND", "");
    return out;
}

}  // namespace

TEST_CASE("Every PNG row filter is undone exactly, on the first row and after, for 1 to 4 bytes a pixel", "[datasets][png]") {
    std::mt19937 rng(5);
    for (const auto& [channels, bit_depth] : std::vector<std::pair<int, int>>{{1, 8}, {2, 8}, {3, 8}, {4, 8}, {1, 16}})
        for (const std::vector<int>& filters : std::vector<std::vector<int>>{{0}, {1}, {2}, {3}, {4}, {3, 4, 1, 2, 0}}) {
            INFO(channels << " channels, " << bit_depth << " bits, filters starting " << filters[0]);
            HandPng png{37, 11, channels, bit_depth, {}};
            png.raw.resize(static_cast<std::size_t>(png.width * png.height * channels * bit_depth / 8));
            for (auto& b : png.raw) b = static_cast<uint8_t>(rng());
            const std::string file = encode(png, filters);
            const auto raster = files::decode_png_raster(reinterpret_cast<const uint8_t*>(file.data()), file.size());
            REQUIRE(raster);
            const std::size_t row_bytes = png.raw.size() / png.height;
            for (int y = 0; y < png.height; ++y)
                REQUIRE(std::memcmp(raster->pixels.data() + y * raster->stride + 1, png.raw.data() + y * row_bytes, row_bytes) == 0);
            // And libpng (cv::imread) reads the hand-made file as this path does.
            test::TempDir tmp;
            const fs::path path = tmp.path() / "hand.png";
            write_bytes(path, file);
            const int flags = bit_depth == 16 ? cv::IMREAD_UNCHANGED : cv::IMREAD_COLOR;
            const cv::Mat ours = files::decode_png(path, flags);
            REQUIRE_FALSE(ours.empty());
            require_same(ours, cv::imread(path.string(), flags));
        }
}

TEST_CASE("PNG decoding gives cv::imread's pixels for every kind it takes, and leaves the others to it", "[datasets][png]") {
    test::TempDir tmp;
    struct Case {
        const char* name;
        int type, flags;
        bool fast;  // the libdeflate path decodes it (else decode_png declines and cv::imread does)
    };
    const Case cases[] = {
        {"8-bit BGR as colour", CV_8UC3, cv::IMREAD_COLOR, true},    {"8-bit BGRA as colour", CV_8UC4, cv::IMREAD_COLOR, true},
        {"8-bit grey as colour", CV_8UC1, cv::IMREAD_COLOR, true},   {"16-bit grey as depth", CV_16UC1, cv::IMREAD_UNCHANGED, true},
        {"16-bit BGR as colour", CV_16UC3, cv::IMREAD_COLOR, false}, {"8-bit grey unchanged", CV_8UC1, cv::IMREAD_UNCHANGED, false},
        {"16-bit grey as colour", CV_16UC1, cv::IMREAD_COLOR, false}};
    uint32_t seed = 1;
    for (const Case& c : cases)
        for (int level : {0, 1, 9}) {
            INFO(c.name << ", compression " << level);
            const fs::path file = tmp.path() / ("image-" + std::to_string(seed) + ".png");
            REQUIRE(cv::imwrite(file.string(), test_image(c.type, seed++), {cv::IMWRITE_PNG_COMPRESSION, level}));
            const cv::Mat reference = cv::imread(file.string(), c.flags);
            CHECK(files::decode_png(file, c.flags).empty() == !c.fast);
            require_same(files::load_image(file, c.flags), reference);
        }
}

TEST_CASE("PNG decoding of the real TUM frames equals cv::imread's", "[datasets][png][reference]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    int compared = 0;
    for (const char* sub : {"rgb", "depth"}) {
        const int flags = std::string(sub) == "rgb" ? cv::IMREAD_COLOR : cv::IMREAD_UNCHANGED;
        int k = 0;
        for (const auto& entry : fs::directory_iterator(dir / sub)) {
            if (k++ % 15) continue;  // six of each
            const cv::Mat fast = files::decode_png(entry.path(), flags);
            REQUIRE_FALSE(fast.empty());
            require_same(fast, cv::imread(entry.path().string(), flags));
            ++compared;
        }
    }
    CHECK(compared >= 10);
}

TEST_CASE("A broken PNG is an error naming the file, whichever decoder meets it", "[datasets][png]") {
    test::TempDir tmp;
    const fs::path good = tmp.path() / "good.png";
    REQUIRE(cv::imwrite(good.string(), test_image(CV_8UC3, 7)));
    const std::string bytes = bytes_of(good);

    const fs::path truncated = tmp.path() / "truncated.png";
    write_bytes(truncated, bytes.substr(0, bytes.size() / 2));
    CHECK_THAT(error_of(truncated, cv::IMREAD_COLOR), Contains(truncated.string()) && Contains("cannot decode image"));

    // One byte changed inside the image data: the chunk's CRC no longer matches.
    std::string flipped = bytes;
    flipped[bytes.find("IDAT") + 40] ^= 0x5a;
    const fs::path bad_crc = tmp.path() / "bad_crc.png";
    write_bytes(bad_crc, flipped);
    CHECK_THAT(error_of(bad_crc, cv::IMREAD_COLOR), Contains(bad_crc.string()) && Contains("cannot decode image"));

    // Not a PNG at all, though named one: cv::imread's turn, and its message.
    const fs::path text = tmp.path() / "text.png";
    write_bytes(text, "not a png");
    CHECK(files::decode_png(text, cv::IMREAD_COLOR).empty());
    CHECK_THAT(error_of(text, cv::IMREAD_COLOR), Contains(text.string()) && Contains("cannot decode image"));

    // A header that claims 100000 × 100000 pixels is not decoded by this path.
    std::string huge = bytes;
    const std::size_t ihdr = huge.find("IHDR") + 4;
    for (int i = 0; i < 2; ++i) {
        huge[ihdr + 4 * i + 1] = 0x01, huge[ihdr + 4 * i + 2] = static_cast<char>(0x86), huge[ihdr + 4 * i + 3] = static_cast<char>(0xa0);
        huge[ihdr + 4 * i] = 0;
    }
    const fs::path claims = tmp.path() / "huge.png";
    write_bytes(claims, huge);
    CHECK_THAT(error_of(claims, cv::IMREAD_COLOR), Contains(claims.string()));
}

TEST_CASE("Colour and depth decoded together equal each decoded alone, errors included", "[datasets][png]") {
    test::TempDir tmp;
    const fs::path color = tmp.path() / "c.png", depth = tmp.path() / "d.png", missing = tmp.path() / "none.png";
    REQUIRE(cv::imwrite(color.string(), test_image(CV_8UC3, 3)));
    REQUIRE(cv::imwrite(depth.string(), test_image(CV_16UC1, 4)));
    const auto both = files::load_color_and_depth(color, cv::IMREAD_COLOR, depth, cv::IMREAD_UNCHANGED);
    require_same(both.color, cv::imread(color.string(), cv::IMREAD_COLOR));
    require_same(both.depth, cv::imread(depth.string(), cv::IMREAD_UNCHANGED));
    CHECK_THROWS_WITH(files::load_color_and_depth(color, cv::IMREAD_COLOR, missing, cv::IMREAD_UNCHANGED),
                      Contains(missing.string()) && Contains("missing file"));
    CHECK_THROWS_WITH(files::load_color_and_depth(missing, cv::IMREAD_COLOR, depth, cv::IMREAD_UNCHANGED),
                      Contains(missing.string()) && Contains("missing file"));
}
