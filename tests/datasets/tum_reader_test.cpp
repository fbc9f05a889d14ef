#include "abi/instances.hpp"
#include "test_support.hpp"
#include "track/track.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>

#include <fstream>

using namespace vobench;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

PluginPtr tum() { return PluginLibrary::load(test::plugin("tum")); }

// A small valid TUM folder: 3 frames of 64×48, colour and depth 5 ms apart, ground truth at 100 Hz.
void write_sequence(const fs::path& dir, int frames = 3) {
    fs::create_directories(dir / "rgb");
    fs::create_directories(dir / "depth");
    std::ofstream rgb(dir / "rgb.txt"), depth(dir / "depth.txt"), gt(dir / "groundtruth.txt");
    rgb << "# color images\n# file: 'x.bag'\n# timestamp filename\n";
    depth << "# depth maps\n";
    gt << "# ground truth\n";
    for (int i = 0; i < frames; ++i) {
        const double t = 100.0 + 0.1 * i;
        const std::string name = std::to_string(i) + ".png";
        cv::imwrite((dir / "rgb" / name).string(), cv::Mat(48, 64, CV_8UC3, cv::Scalar(10 * i, 20, 30)));
        cv::imwrite((dir / "depth" / name).string(), cv::Mat(48, 64, CV_16UC1, cv::Scalar(5000 + i)));
        rgb << std::fixed << t << " rgb/" << name << "\n";
        depth << std::fixed << t + 0.005 << " depth/" << name << "\n";
    }
    for (int k = 0; k < frames * 10; ++k) gt << std::fixed << 100.0 + 0.01 * k << " " << 0.01 * k << " 0 0 0 0 0 1\n";
}

std::string open_error(const fs::path& dir, const ParamMap& options = {}) {
    return test::read_all_error(test::plugin("tum"), dir, options);
}

}  // namespace

TEST_CASE("tum reads the real fr1/rpy sample: 90 associated frames of 640x480 with ground truth", "[datasets][tum]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_rpy");
    DatasetInstance d(tum());
    d.open(dir.string(), {{"intrinsics", "fr1"}});
    const vobench_sequence_info& info = d.info();
    CHECK(info.frame_count == 90);  // associate.py gives 90 pairs
    CHECK(info.camera->width == 640);
    CHECK(info.camera->height == 480);
    CHECK(info.camera->fx == 517.3);
    CHECK(info.camera->distortion_count == 5);
    CHECK(info.depth_scale == 1.0 / 5000.0);
    CHECK(info.gt_count == 307);
    const vobench_frame& f = d.read(89);
    CHECK(f.timestamp == 1305031232.493650);
    CHECK(std::abs(f.depth_timestamp - f.timestamp) < 0.02);
    CHECK(f.depth->format == VOBENCH_PIXEL_DEPTH_U16);
}

TEST_CASE("tum reads the 9-frame fr1/desk sample", "[datasets][tum]") {
    VOBENCH_REQUIRE_DATA(dir, "real/rgbd_dataset_freiburg1_desk");
    DatasetInstance d(tum());
    d.open(dir.string(), {});
    CHECK(d.info().frame_count == 9);
    CHECK(d.info().camera->fx == 517.3);  // guessed from the folder name
}

TEST_CASE("tum delivers what it wrote, undistorted on request", "[datasets][tum]") {
    test::TempDir tmp;
    write_sequence(tmp.path());
    DatasetInstance d(tum());
    d.open(tmp.path().string(), {{"intrinsics", "fr3"}});
    CHECK(d.info().frame_count == 3);
    CHECK(d.info().gt_count == 30);
    const vobench_frame& f = d.read(2);
    CHECK(f.index == 2);
    CHECK(static_cast<const uint16_t*>(f.depth->data)[0] == 5002);
    CHECK(static_cast<const uint8_t*>(f.color->data)[0] == 20);  // B of BGR (10*2, 20, 30)
    DatasetInstance u(tum());
    u.open(tmp.path().string(), {{"intrinsics", "fr1"}, {"undistort", "true"}});
    CHECK(u.info().camera->distortion_count == 0);
    CHECK(u.read(0).color->width == 64);
}

TEST_CASE("tum: each bad input is a clear error naming the file and line", "[datasets][tum]") {
    test::TempDir tmp;
    const fs::path dir = tmp.path() / "seq";

    SECTION("missing list file") {
        write_sequence(dir);
        fs::remove(dir / "depth.txt");
        CHECK_THAT(open_error(dir), Contains("depth.txt: cannot open file"));
    }
    SECTION("malformed list line") {
        write_sequence(dir);
        std::ofstream(dir / "rgb.txt", std::ios::app) << "abc rgb/x.png\n";
        CHECK_THAT(open_error(dir), Contains("rgb.txt:7: expected `timestamp path`, the stamp 'abc' is not a number"));
    }
    SECTION("empty sequence") {
        write_sequence(dir);
        std::ofstream(dir / "rgb.txt") << "# nothing here\n";
        CHECK_THAT(open_error(dir), Contains("rgb.txt: no entries (empty sequence)"));
    }
    SECTION("missing image") {
        write_sequence(dir);
        fs::remove(dir / "depth" / "1.png");
        CHECK_THAT(open_error(dir), Contains("depth/1.png: missing file"));
    }
    SECTION("corrupt (truncated) PNG") {
        write_sequence(dir);
        fs::resize_file(dir / "rgb" / "2.png", 40);
        CHECK_THAT(open_error(dir), Contains("rgb/2.png: cannot decode image"));
    }
    SECTION("8-bit depth where 16-bit is expected") {
        write_sequence(dir);
        cv::imwrite((dir / "depth" / "1.png").string(), cv::Mat(48, 64, CV_8UC1, cv::Scalar(7)));
        CHECK_THAT(open_error(dir), Contains("depth/1.png: depth must be a 16-bit single-channel PNG, found 8-bit"));
    }
    SECTION("colour and depth sizes differ") {
        write_sequence(dir);
        cv::imwrite((dir / "depth" / "1.png").string(), cv::Mat(24, 32, CV_16UC1, cv::Scalar(7)));
        CHECK_THAT(open_error(dir), Contains("depth/1.png is 32x24"));
    }
    SECTION("malformed ground truth") {
        write_sequence(dir);
        std::ofstream(dir / "groundtruth.txt", std::ios::app) << "101.0 1 2\n";
        CHECK_THAT(open_error(dir), Contains("groundtruth.txt:32: expected 8 values, found 3"));
    }
    SECTION("reading past the end") {
        write_sequence(dir);
        DatasetInstance d(tum());
        d.open(dir.string(), {});
        CHECK_THROWS_WITH(d.read(3), Contains("frame 3 is past the end (3 frames)"));
    }
    SECTION("unknown option") {
        write_sequence(dir);
        CHECK_THAT(open_error(dir, {{"intrinsic", "fr1"}}), Contains("plugin 'tum' has no parameter 'intrinsic'"));
    }
}

TEST_CASE("a frame that cannot be decoded ends the run there and keeps the poses before it", "[datasets][tum][track]") {
    test::TempDir tmp;
    write_sequence(tmp.path(), 5);
    fs::resize_file(tmp.path() / "rgb" / "3.png", 40);
    TrackOptions o;
    o.dataset = "tum";
    o.path = tmp.path().string();
    o.algorithm = "constant_pose";
    const TrackResult r = run_track(o, PluginRegistry({VOBENCH_PLUGIN_DIR}));  // frames decoded ahead on another thread
    CHECK_THAT(r.error, Contains("reading frame 3:") && Contains("rgb/3.png: cannot decode image"));
    CHECK(r.estimate.size() == 3);
    CHECK(r.estimate[2].t == Approx(100.2));
}
