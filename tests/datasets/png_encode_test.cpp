// vobench synth's PNG encoder (plugins/common/png_encode.cpp) against libpng, as a reader would meet
// its files: cv::imread (libpng) and the readers' own decoder must give back exactly the pixels
// encoded, for every type the renderer writes, at shapes where the row filter's edge cases show.
#include "png_encode.hpp"  // plugins/common
#include "png_raster.hpp"  // plugins/common
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <stdexcept>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

// Every byte value (noise), flat rows and a ramp: the Average filter's left/up cases and wrap-around.
cv::Mat noisy_image(int type, cv::Size size, uint32_t seed) {
    cv::Mat m(size, type);
    cv::theRNG().state = seed;
    const double top = CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256;
    cv::randu(m, cv::Scalar::all(0), cv::Scalar::all(top));
    for (int y = 0; y < m.rows / 3; ++y) m.row(y).setTo(cv::Scalar::all(std::fmod(y * 977.0, top)));
    return m;
}

}  // namespace

TEST_CASE("png_encode: libpng and the readers' decoder read back exactly the pixels encoded", "[png][synth]") {
    const test::TempDir tmp;
    const int types[] = {CV_8UC3, CV_8UC1, CV_16UC1};
    const cv::Size sizes[] = {{1, 1}, {1, 7}, {2, 3}, {131, 97}, {640, 480}};
    uint32_t seed = 1;
    for (const int type : types)
        for (const cv::Size size : sizes)
            for (const int level : {1, 6}) {
                CAPTURE(type, size.width, size.height, level);
                const cv::Mat image = noisy_image(type, size, seed++);
                const fs::path path = tmp.path() / "image.png";
                files::write_png(path, image, level);
                const cv::Mat back = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
                REQUIRE(back.type() == image.type());
                REQUIRE(back.size() == image.size());
                CHECK(cv::norm(back, image, cv::NORM_INF) == 0);

                const std::vector<uint8_t> bytes = files::encode_png(image, level);
                const auto raster = files::decode_png_raster(bytes.data(), bytes.size());
                REQUIRE(raster);
                CHECK(raster->width == static_cast<uint32_t>(size.width));
                CHECK(raster->bit_depth == (type == CV_16UC1 ? 16 : 8));
                CHECK(raster->channels == CV_MAT_CN(type));
            }
}

TEST_CASE("png_encode: smaller than cv::imwrite at zlib level 1 on a rendered-like frame", "[png][synth]") {
    // A smooth image with sensor noise, as the renderer writes: the fixed Average filter must not
    // cost size against libpng's per-row choice (the reason for the encoder is speed, not size).
    cv::Mat image(480, 640, CV_8UC3);
    for (int y = 0; y < image.rows; ++y)
        for (int x = 0; x < image.cols; ++x) image.at<cv::Vec3b>(y, x) = cv::Vec3b(x / 3, y / 2, (x + y) / 5);
    cv::Mat noise(image.size(), CV_8UC3);
    cv::theRNG().state = 5;
    cv::randn(noise, cv::Scalar::all(0), cv::Scalar::all(1));
    image += noise;
    std::vector<uchar> reference;
    REQUIRE(cv::imencode(".png", image, reference, {cv::IMWRITE_PNG_COMPRESSION, 1}));
    CHECK(files::encode_png(image, 1).size() < reference.size());
}

TEST_CASE("png_encode: an image it cannot store is refused, an unwritable path named", "[png][synth]") {
    CHECK_THROWS_AS(files::encode_png(cv::Mat(4, 4, CV_32FC1, cv::Scalar(1))), std::invalid_argument);
    CHECK_THROWS_AS(files::encode_png(cv::Mat(4, 4, CV_8UC4, cv::Scalar(1))), std::invalid_argument);
    CHECK_THROWS_AS(files::encode_png(cv::Mat()), std::invalid_argument);
    CHECK_THROWS_AS(files::encode_png(cv::Mat(4, 4, CV_8UC1, cv::Scalar(1)), 13), std::invalid_argument);
    const test::TempDir tmp;
    try {
        files::write_png(tmp.path() / "no" / "such" / "dir.png", cv::Mat(4, 4, CV_8UC1, cv::Scalar(1)));
        FAIL("no exception");
    } catch (const std::runtime_error& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("dir.png"));
    }
}
