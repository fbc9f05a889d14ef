// The putk2 reader on sequences the generator wrote in every layout (round trips), on PUTK²'s real
// calibration file, and on bad input.
#include "abi/instances.hpp"
#include "synth/sequence_writer.hpp"
#include "test_support.hpp"
#include "track/track.hpp"

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <fstream>

using namespace vobench;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

PluginPtr reader(const std::string& name) { return PluginLibrary::load(test::plugin(name)); }

fs::path render(const fs::path& root, const std::string& sensor, const std::string& layout, uint64_t frames = 3) {
    synth::SynthOptions o;
    o.sensor = sensor;
    o.trajectory = "speed2";
    o.frames = frames;
    o.layout = layout;
    o.out = root / (sensor + "-" + layout);
    synth::synthesize(o);
    return o.out;
}

cv::Mat depth_metres(const vobench_frame& f) {
    const vobench_image& d = *f.depth;
    cv::Mat m(d.height, d.width, d.format == VOBENCH_PIXEL_DEPTH_U16 ? CV_16UC1 : CV_32FC1, const_cast<void*>(d.data),
              static_cast<std::size_t>(d.stride_bytes));
    cv::Mat out;
    m.convertTo(out, CV_32F, f.depth_scale);
    return out;
}

cv::Mat color_of(const vobench_frame& f) {
    return cv::Mat(f.color->height, f.color->width, CV_8UC3, const_cast<void*>(f.color->data),
                   static_cast<std::size_t>(f.color->stride_bytes))
        .clone();
}

std::string open_error(const fs::path& dir, const ParamMap& options = {}) {
    return test::read_all_error(test::plugin("putk2"), dir, options);
}

}  // namespace

TEST_CASE("putk2 reads both PUTK² layouts back as the TUM layout has them: poses, pixels, depth", "[datasets][putk2]") {
    test::TempDir tmp;
    for (const std::string sensor : {"kinect1", "kinect2"}) {
        const fs::path tum_dir = render(tmp.path(), sensor, "tum");
        DatasetInstance tum(reader("tum"));
        tum.open(tum_dir.string(), {});
        const metrics::Trajectory tum_gt = ground_truth_of(tum.info());
        for (const std::string layout : {"putk2", "putk2-tum"}) {
            INFO(sensor << " " << layout);
            const fs::path dir = render(tmp.path(), sensor, layout);
            DatasetInstance d(reader("putk2"));
            d.open(dir.string(), {});
            REQUIRE(d.info().frame_count == 3);
            CHECK(std::string(d.info().sensor) == sensor);
            CHECK(d.info().camera->fx == tum.info().camera->fx);
            // Ground truth: the same poses at the same stamps (frame / 10 s), to 1e-9.
            const metrics::Trajectory gt = ground_truth_of(d.info());
            REQUIRE(gt.size() == tum_gt.size());
            for (std::size_t k = 0; k < gt.size(); ++k) {
                CHECK(std::abs(gt[k].t - tum_gt[k].t) < 1e-9);
                CHECK((gt[k].isometry().matrix() - tum_gt[k].isometry().matrix()).cwiseAbs().maxCoeff() < 1e-9);
            }
            // And from the raw marker trajectory (eq. 10).
            DatasetInstance raw(reader("putk2"));
            raw.open(dir.string(), {{"ground_truth", "raw"}});
            const metrics::Trajectory raw_gt = ground_truth_of(raw.info());
            CHECK((raw_gt[2].isometry().matrix() - gt[2].isometry().matrix()).cwiseAbs().maxCoeff() < 1e-9);
            for (uint64_t i = 0; i < 3; ++i) {
                const cv::Mat c_tum = color_of(tum.read(i)), d_tum = depth_metres(tum.read(i));
                const cv::Mat c = color_of(d.read(i)), dm = depth_metres(d.read(i));
                CHECK(cv::norm(c, c_tum, cv::NORM_INF) == 0);
                REQUIRE(dm.size() == d_tum.size());
                // Within depth quantisation: 1 mm (PUTK²) and 0.2 mm (TUM) steps, both rounded.
                const cv::Mat both = (dm > 0) & (d_tum > 0);
                const cv::Mat either = (dm > 0) | (d_tum > 0);
                CHECK(cv::countNonZero(both) >= 0.99 * cv::countNonZero(either));
                cv::Mat diff;
                cv::absdiff(dm, d_tum, diff);
                std::vector<float> diffs;
                for (int y = 0; y < diff.rows; ++y)
                    for (int x = 0; x < diff.cols; ++x)
                        if (both.at<uchar>(y, x)) diffs.push_back(diff.at<float>(y, x));
                std::nth_element(diffs.begin(), diffs.begin() + static_cast<long>(diffs.size() * 0.99), diffs.end());
                CHECK(diffs[static_cast<std::size_t>(diffs.size() * 0.99)] <= 0.0006f);
            }
        }
    }
}

TEST_CASE("putk2 reads PUT's real camData.txt and its built-in values equal it", "[datasets][putk2][reference]") {
    VOBENCH_REQUIRE_DATA(real, "putk2-groundtruth");
    test::TempDir tmp;
    const fs::path dir = render(tmp.path(), "kinect1", "putk2", 1);
    fs::remove(dir / "camData.txt");
    DatasetInstance builtin(reader("putk2"));
    builtin.open(dir.string(), {});
    DatasetInstance from_file(reader("putk2"));
    from_file.open(dir.string(), {{"calibration", (real / "camData.txt").string()}});
    const vobench_camera& a = *builtin.info().camera;
    const vobench_camera& b = *from_file.info().camera;
    CHECK(b.fx == 532.77250);
    CHECK(a.fx == b.fx);
    CHECK(a.fy == b.fy);
    CHECK(a.cx == b.cx);
    CHECK(a.cy == b.cy);
    for (int i = 0; i < 8; ++i) CHECK(a.distortion[i] == b.distortion[i]);
    CHECK_THAT(open_error(dir, {{"calibration", (real / "camData.txt").string()}, {"camera_id", "12345"}}),
               Contains("no camera 12345 (it has 21162137, 21238112, 21238113, 21238114, 21238115, 00033000, 00011000, 00022000)"));
}

TEST_CASE("putk2: bad input is a clear error naming the file and line", "[datasets][putk2]") {
    test::TempDir tmp;
    const fs::path dir = render(tmp.path(), "kinect2", "putk2", 2);
    SECTION("malformed camData line") {
        std::ofstream(dir / "camData.txt") << "00033000, 1078.7, 1076.5, 952.7\n";
        CHECK_THAT(open_error(dir),
                   Contains("camData.txt:1: expected `id, fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6` (13 values), found 4"));
    }
    SECTION("malformed matched line") {
        std::ofstream(dir / "matched.txt", std::ios::app) << "x rgb_00009.png\n";
        CHECK_THAT(open_error(dir), Contains("matched.txt:4: expected `frame rgb_file depth_file`"));
    }
    SECTION("frame number out of range (found by fuzz_lists)") {
        std::ofstream(dir / "matched.txt", std::ios::app) << "88888888888888888888 rgb_00001.png depth_00001.png\n";
        CHECK_THAT(open_error(dir), Contains("matched.txt:4: the frame number is not an integer in [0, 2^53]"));
    }
    SECTION("missing depth image") {
        fs::remove(dir / "depth_00001.png");
        CHECK_THAT(open_error(dir), Contains("depth_00001.png: missing file"));
    }
    SECTION("8-bit depth") {
        cv::imwrite((dir / "depth_00001.png").string(), cv::Mat(424, 512, CV_8UC1, cv::Scalar(9)));
        CHECK_THAT(open_error(dir), Contains("depth_00001.png: depth must be a 16-bit single-channel PNG, found 8-bit"));
    }
    SECTION("depth of the wrong size") {
        cv::imwrite((dir / "depth_00001.png").string(), cv::Mat(240, 320, CV_16UC1, cv::Scalar(900)));
        CHECK_THAT(open_error(dir), Contains("depth_00001.png: Kinect v2 depth is 320x240, expected 512x424 or 1920x1080"));
    }
    SECTION("malformed depth camera file") {
        std::ofstream(dir / "depth_camera.txt") << "365 365 255\n0 0 0 1 0 0 0\n";
        CHECK_THAT(open_error(dir), Contains("depth_camera.txt:1: expected `fx fy cx cy`"));
    }
    SECTION("not a PUTK² folder") {
        fs::remove(dir / "matched.txt");
        CHECK_THAT(open_error(dir), Contains("neither matched.txt nor rgb.txt"));
    }
}
