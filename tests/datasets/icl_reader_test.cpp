// The icl_nuim reader on sequences the generator wrote in ICL-NUIM's TUM-compatible layout (stored
// upside down, fy < 0), against the same sequence in the TUM layout.
#include "abi/instances.hpp"
#include "synth/sequence_writer.hpp"
#include "test_support.hpp"
#include "track/track.hpp"

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>

#include <fstream>

using namespace vobench;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

fs::path render(const fs::path& root, const std::string& layout) {
    synth::SynthOptions o;
    o.sensor = "kinect1";
    o.trajectory = "speed2";
    o.frames = 6;
    o.layout = layout;
    o.out = root / layout;
    synth::synthesize(o);
    return o.out;
}

std::string open_error(const fs::path& dir) { return test::read_all_error(test::plugin("icl_nuim"), dir); }

}  // namespace

TEST_CASE("icl_nuim presents fy > 0 and the same pixels and poses as the TUM layout", "[datasets][icl]") {
    test::TempDir tmp;
    const fs::path tum_dir = render(tmp.path(), "tum"), icl_dir = render(tmp.path(), "icl-tum");
    DatasetInstance tum(PluginLibrary::load(test::plugin("tum")));
    tum.open(tum_dir.string(), {});
    DatasetInstance icl(PluginLibrary::load(test::plugin("icl_nuim")));
    icl.open(icl_dir.string(), {{"frame_rate", "10"}});
    const vobench_camera& a = *tum.info().camera;
    const vobench_camera& b = *icl.info().camera;
    CHECK(b.fy > 0);
    CHECK(b.fy == Approx(a.fy));
    CHECK(b.cy == Approx(a.cy));
    for (int i = 0; i < 8; ++i) CHECK(b.distortion[i] == Approx(a.distortion[i]).margin(1e-15));
    const auto gt_tum = ground_truth_of(tum.info()), gt_icl = ground_truth_of(icl.info());
    REQUIRE(gt_icl.size() == gt_tum.size());
    for (std::size_t k = 0; k < gt_icl.size(); ++k) {
        CHECK(gt_icl[k].t == Approx(gt_tum[k].t));
        CHECK((gt_icl[k].isometry().matrix() - gt_tum[k].isometry().matrix()).cwiseAbs().maxCoeff() < 1e-12);
    }
    for (uint64_t i = 0; i < 6; i += 5) {
        const vobench_frame& fi = icl.read(i);
        const cv::Mat ci(fi.color->height, fi.color->width, CV_8UC3, const_cast<void*>(fi.color->data),
                         static_cast<std::size_t>(fi.color->stride_bytes));
        const cv::Mat di(fi.depth->height, fi.depth->width, CV_16UC1, const_cast<void*>(fi.depth->data),
                         static_cast<std::size_t>(fi.depth->stride_bytes));
        const cv::Mat ci_copy = ci.clone(), di_copy = di.clone();
        const vobench_frame& ft = tum.read(i);
        const cv::Mat ct(ft.color->height, ft.color->width, CV_8UC3, const_cast<void*>(ft.color->data),
                         static_cast<std::size_t>(ft.color->stride_bytes));
        const cv::Mat dt(ft.depth->height, ft.depth->width, CV_16UC1, const_cast<void*>(ft.depth->data),
                         static_cast<std::size_t>(ft.depth->stride_bytes));
        CHECK(cv::norm(ci_copy, ct, cv::NORM_INF) == 0);
        CHECK(cv::norm(di_copy, dt, cv::NORM_INF) == 0);
    }
}

TEST_CASE("icl_nuim: frames without a pose are delivered, and evaluation matches the rest", "[datasets][icl]") {
    test::TempDir tmp;
    const fs::path dir = render(tmp.path(), "icl-tum");
    // Drop the pose of frame 2 from the ground truth.
    std::ifstream in(dir / "synth.gt.freiburg");
    std::string line, kept;
    while (std::getline(in, line))
        if (line.rfind("2 ", 0) != 0) kept += line + "\n";
    in.close();
    std::ofstream(dir / "synth.gt.freiburg") << kept;
    TrackOptions o;
    o.dataset = "icl_nuim";
    o.path = dir.string();
    o.algorithm = "put_vo";
    const TrackResult r = run_track(o, PluginRegistry({VOBENCH_PLUGIN_DIR}));
    CHECK(r.frames.size() == 6);
    REQUIRE(r.evaluation);
    CHECK(r.evaluation->ate->association.matches.size() == 5);
    CHECK(r.evaluation->ate->association.unmatched_second == 1);
}

TEST_CASE("icl_nuim: bad input names the file and line", "[datasets][icl]") {
    test::TempDir tmp;
    const fs::path dir = render(tmp.path(), "icl-tum");
    SECTION("malformed associations line") {
        std::ofstream(dir / "associations.txt", std::ios::app) << "7 depth/7.png\n";
        CHECK_THAT(open_error(dir), Contains("associations.txt:7: expected `t_depth depth_file t_rgb rgb_file`"));
    }
    SECTION("malformed camera file") {
        std::ofstream(dir / "camera.txt") << "481.2 -480\n";
        CHECK_THAT(open_error(dir), Contains("camera.txt:1: expected `fx fy cx cy`"));
    }
    SECTION("missing image") {
        fs::remove(dir / "rgb" / "4.png");
        CHECK_THAT(open_error(dir), Contains("rgb/4.png: missing file"));
    }
}

TEST_CASE("icl_nuim reads the POV-Ray layout: ray distances to z, poses from camera vectors and .gt.sim", "[datasets][icl]") {
    test::TempDir tmp;
    const fs::path tum_dir = render(tmp.path(), "tum"), pov_dir = render(tmp.path(), "icl-povray");
    DatasetInstance tum(PluginLibrary::load(test::plugin("tum")));
    tum.open(tum_dir.string(), {});
    for (const std::string gt_file : {"", "synth.gt.sim"}) {
        INFO("ground truth from " << (gt_file.empty() ? "camera vectors" : gt_file));
        DatasetInstance pov(PluginLibrary::load(test::plugin("icl_nuim")));
        ParamMap options{{"frame_rate", "10"}};
        if (!gt_file.empty()) options["ground_truth"] = (pov_dir / gt_file).string();
        pov.open(pov_dir.string(), options);
        CHECK(pov.info().frame_count == 6);
        CHECK(pov.info().camera->fy == Approx(tum.info().camera->fy));
        const auto a = ground_truth_of(tum.info()), b = ground_truth_of(pov.info());
        REQUIRE(a.size() == b.size());
        for (std::size_t k = 0; k < a.size(); ++k) {
            CHECK(b[k].t == Approx(a[k].t));
            CHECK((b[k].isometry().matrix() - a[k].isometry().matrix()).cwiseAbs().maxCoeff() < 1e-9);
        }
    }
    DatasetInstance pov(PluginLibrary::load(test::plugin("icl_nuim")));
    pov.open(pov_dir.string(), {});
    const vobench_frame& fp = pov.read(3);
    const cv::Mat zp = cv::Mat(fp.depth->height, fp.depth->width, CV_32F, const_cast<void*>(fp.depth->data),
                               static_cast<std::size_t>(fp.depth->stride_bytes))
                           .clone();
    const cv::Mat cp = cv::Mat(fp.color->height, fp.color->width, CV_8UC3, const_cast<void*>(fp.color->data),
                               static_cast<std::size_t>(fp.color->stride_bytes))
                           .clone();
    const vobench_frame& ft = tum.read(3);
    cv::Mat zt;
    cv::Mat(ft.depth->height, ft.depth->width, CV_16UC1, const_cast<void*>(ft.depth->data),
            static_cast<std::size_t>(ft.depth->stride_bytes))
        .convertTo(zt, CV_32F, ft.depth_scale);
    const cv::Mat ct(ft.color->height, ft.color->width, CV_8UC3, const_cast<void*>(ft.color->data),
                     static_cast<std::size_t>(ft.color->stride_bytes));
    CHECK(cv::norm(cp, ct, cv::NORM_INF) == 0);
    // z from ray distances (6 decimals) against the TUM layout's 1/5000 m steps.
    CHECK(cv::norm(zp, zt, cv::NORM_INF) <= 0.00011);
    CHECK(cv::countNonZero(zp > 0) == cv::countNonZero(zt > 0));
}

TEST_CASE("icl_nuim POV-Ray layout: bad input names the file", "[datasets][icl]") {
    test::TempDir tmp;
    const fs::path dir = render(tmp.path(), "icl-povray");
    SECTION("too few depth values") {
        std::ofstream(dir / "scene_00_0002.depth") << "1.0 2.0 3.0\n";
        CHECK_THAT(open_error(dir), Contains("scene_00_0002.depth: value 4 of 307200 is missing or not a number"));
    }
    SECTION("camera vectors without cam_dir") {
        std::ofstream(dir / "scene_00_0001.txt") << "cam_pos = [0, 0, 0]';\ncam_up = [0, 1, 0]';\n";
        CHECK_THAT(open_error(dir), Contains("scene_00_0001.txt: no cam_dir"));
    }
}
