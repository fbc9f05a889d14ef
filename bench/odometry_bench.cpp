// Reader speed (each reader alone, 640×480 and 1920×1080), and odometry speed, side by side in one run: put_vo vs OpenCV's RgbdOdometry
// (opencv_rgbd) on the same frames, already decoded in memory, OpenCV limited to one thread — per frame time inside process(). Frames:
// synthetic Kinect v1 (640×480) and Kinect v2 (1920×1080) sequences rendered first, and the real TUM fr1/rpy sample when ../shared/data is
// present. Also the renderer's frames/s per sensor.
#include "abi/instances.hpp"
#include "abi/plugin_registry.hpp"
#include "synth/sequence_writer.hpp"
#include "track/frame_cache.hpp"
#include "track/frame_prefetcher.hpp"
#include "util/frame_memory.hpp"

#include "dataset_files.hpp"       // plugins/common
#include "depth_registration.hpp"  // plugins/common
#include "lk_tracker.hpp"          // plugins/odometry/put_vo
#include "png_decode.hpp"          // plugins/common

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

using namespace vobench;
namespace fs = std::filesystem;

namespace {

struct Sequence {
    vobench_camera camera{};
    std::vector<std::unique_ptr<OwnedFrame>> frames;
};

// The build's plugins; folders in $VOBENCH_PLUGIN_PATH come first, so an older build's reader can be
// measured against today's decode-only reference (VOBENCH_PLUGIN_PATH=old/build/plugins).
const PluginRegistry& registry() {
    static const PluginRegistry r([] {
        std::vector<fs::path> folders;
        std::stringstream path(std::getenv("VOBENCH_PLUGIN_PATH") ? std::getenv("VOBENCH_PLUGIN_PATH") : "");
        for (std::string folder; std::getline(path, folder, ':');)
            if (!folder.empty()) folders.emplace_back(folder);
        folders.emplace_back(VOBENCH_PLUGIN_DIR);
        return folders;
    }());
    return r;
}

Sequence load(const fs::path& path, const ParamMap& options) {
    DatasetInstance d(registry().load("tum", VOBENCH_KIND_DATASET));
    d.open(path.string(), options);
    Sequence s;
    s.camera = *d.info().camera;
    for (uint64_t i = 0; i < d.info().frame_count; ++i) s.frames.push_back(std::make_unique<OwnedFrame>(d.read(i)));
    return s;
}

// A synthetic explore1 sequence rendered once into the temp folder (kept between runs).
fs::path synthetic(const std::string& name, const std::string& sensor, const std::string& layout, uint64_t frames) {
    const fs::path dir = fs::temp_directory_path() / ("vobench-bench-" + name);
    if (!fs::exists(dir / "synth.json")) {
        synth::SynthOptions o;
        o.sensor = sensor;
        o.trajectory = "explore1";
        o.frames = frames;
        o.layout = layout;
        o.out = dir;
        synth::synthesize(o);
    }
    return dir;
}

// The real TUM fr1/rpy sample's folder ($VOBENCH_DATA_DIR, else ../shared/data).
fs::path real_fr1_rpy() {
    const char* env = std::getenv("VOBENCH_DATA_DIR");
    return fs::path(env ? env : VOBENCH_TEST_DATA_DIR) / "real" / "rgbd_dataset_freiburg1_rpy";
}

// The sample's images of one stream ("rgb" or "depth") in stamp order; none (and the benchmark
// skipped) where the sample is absent.
std::vector<fs::path> real_fr1_rpy_images(benchmark::State& state, const std::string& stream) {
    std::vector<fs::path> files;
    const fs::path dir = real_fr1_rpy() / stream;
    if (!fs::exists(dir)) {
        state.SkipWithError("no real TUM sample (VOBENCH_DATA_DIR)");
        return files;
    }
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

const Sequence& sequence(const std::string& name) {
    static std::map<std::string, Sequence> cache;
    auto it = cache.find(name);
    if (it != cache.end()) return it->second;
    if (name == "tum-fr1-rpy") {
        const fs::path p = real_fr1_rpy();
        return cache[name] = fs::exists(p) ? load(p, {{"intrinsics", "fr1"}}) : Sequence{};
    }
    // "kinect1" / "kinect2": 40 frames of explore1.
    return cache[name] = load(synthetic(name, name, "tum", 40), {});
}

void run_odometry(benchmark::State& state, const std::string& plugin, const std::string& data, const ParamMap& params = {}) {
    cv::setNumThreads(1);  // one core, as the targets are stated
    const Sequence& s = sequence(data);
    if (s.frames.empty()) {
        state.SkipWithError("data absent");
        return;
    }
    OdometryInstance odo(registry().load(plugin, VOBENCH_KIND_ODOMETRY));
    odo.start(s.camera, params, 1);
    std::size_t k = 0;
    vobench_pose pose{};
    pose.struct_size = sizeof(pose);
    vobench_tracking_status tracking;
    for (auto _ : state) {
        if (k == s.frames.size()) {  // start the sequence over, outside the timing
            state.PauseTiming();
            odo.reset();
            k = 0;
            state.ResumeTiming();
        }
        if (odo.process(s.frames[k++]->frame, pose, tracking) != VOBENCH_OK) state.SkipWithError(odo.last_error().c_str());
    }
    state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void run_synth(benchmark::State& state, const std::string& sensor) {
    const fs::path dir = fs::temp_directory_path() / ("vobench-bench-synth-" + sensor);
    uint64_t frames = 0;
    for (auto _ : state) {
        synth::SynthOptions o;
        o.sensor = sensor;
        o.trajectory = "explore1";
        o.frames = 4;
        o.out = dir;
        frames += synth::synthesize(o).frames;
    }
    state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
    fs::remove_all(dir);
}

// "rgb_00007.png": the putk2 layout's file names.
std::string fmt_index(const std::string& prefix, int k) {
    char name[32];
    std::snprintf(name, sizeof name, "%s%05d.png", prefix.c_str(), k);
    return name;
}

// A reader alone: frames/s of open-once, read every frame (decode, rescale or register), 10 frames.
void run_reader(benchmark::State& state, const std::string& reader, const std::string& sensor, const std::string& layout) {
    const fs::path dir = synthetic("reader-" + sensor + "-" + layout, sensor, layout, 10);
    DatasetInstance d(registry().load(reader, VOBENCH_KIND_DATASET));
    d.open(dir.string(), {});
    uint64_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(d.read(i++ % d.info().frame_count).depth->data);
    state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The reference for the Kinect v2 frame path (issue #19): only decoding the same PNGs with OpenCV, one
// after the other, nothing registered — putk2 layout: colour 1920×1080 BGR and depth 512×424 16-bit;
// TUM layout (the demo's): both 1920×1080. The readers' delivery (run_reader putk2/kinect2, tum/kinect2)
// is measured against these, in the same run.
void run_decode_only(benchmark::State& state, const std::string& sensor, const std::string& layout) {
    const fs::path dir = synthetic("reader-" + sensor + "-" + layout, sensor, layout, 10);
    std::vector<std::pair<fs::path, fs::path>> files;
    if (layout == "tum") {  // rgb/STAMP.png and depth/STAMP.png, the same stamps when rendered
        std::vector<fs::path> colour;
        for (const auto& e : fs::directory_iterator(dir / "rgb")) colour.push_back(e.path());
        std::sort(colour.begin(), colour.end());
        for (const fs::path& c : colour)
            if (fs::exists(dir / "depth" / c.filename())) files.emplace_back(c, dir / "depth" / c.filename());
    } else {
        for (int k = 0; fs::exists(dir / fmt_index("rgb_", k)); ++k)
            files.emplace_back(dir / fmt_index("rgb_", k), dir / fmt_index("depth_", k));
    }
    if (files.empty()) {
        state.SkipWithError("no colour and depth pairs in the rendered folder");
        return;
    }
    std::size_t i = 0;
    for (auto _ : state) {
        const auto& [color, depth] = files[i++ % files.size()];
        benchmark::DoNotOptimize(cv::imread(color.string(), cv::IMREAD_COLOR).data);
        benchmark::DoNotOptimize(cv::imread(depth.string(), cv::IMREAD_UNCHANGED).data);
    }
    state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The parts of the putk2 reader's Kinect v2 delivery, one at a time on the same files: each PNG decoded
// by cv::imread or by the readers' own path (libdeflate), and the depth registration alone.
void run_decode_part(benchmark::State& state, const std::string& part) {
    const fs::path dir = synthetic("reader-kinect2-putk2", "kinect2", "putk2", 10);
    const bool color = part.find("color") != std::string::npos, own = part.find("own") != std::string::npos;
    const int flags = color ? cv::IMREAD_COLOR : cv::IMREAD_UNCHANGED;
    const fs::path file = dir / fmt_index(color ? "rgb_" : "depth_", 0);
    for (auto _ : state) benchmark::DoNotOptimize((own ? files::decode_png(file, flags) : cv::imread(file.string(), flags)).data);
}

// The same on a real TUM fr1/rpy frame (640×480 colour and 16-bit depth, both rows filtered with Sub).
void run_decode_real(benchmark::State& state, bool own) {
    const std::vector<fs::path> color = real_fr1_rpy_images(state, "rgb");
    if (color.size() <= 10) return;
    const std::vector<fs::path> depth = real_fr1_rpy_images(state, "depth");
    if (depth.size() <= 10) return;
    for (auto _ : state) {
        benchmark::DoNotOptimize(
            (own ? files::decode_png(color[10], cv::IMREAD_COLOR) : cv::imread(color[10].string(), cv::IMREAD_COLOR)).data);
        benchmark::DoNotOptimize(
            (own ? files::decode_png(depth[10], cv::IMREAD_UNCHANGED) : cv::imread(depth[10].string(), cv::IMREAD_UNCHANGED)).data);
    }
}

// The Lucas–Kanade tracker alone, put_vo's settings (7-px window, three levels, 30 iterations or
// 0.01 px), one core: the real fr1/rpy frames' 400 strongest Shi–Tomasi corners tracked into the next
// frame, pyramids and corners prepared outside the timing. `own`: lk_tracker.hpp (OpenCV's result to
// the bit); `integer`: lk_tracker.hpp with integer_sums; otherwise cv::calcOpticalFlowPyrLK.
void run_lucas_kanade(benchmark::State& state, const std::string& implementation) {
    const std::vector<fs::path> color = real_fr1_rpy_images(state, "rgb");
    if (color.size() < 2) return;
    cv::setNumThreads(1);
    put_vo::LkOptions o;
    o.integer_sums = implementation == "integer";
    const bool own = implementation != "opencv";
    const int border = put_vo::lk_pyramid_border(o.window);
    std::vector<std::vector<cv::Mat>> pyramids(color.size());
    std::vector<std::vector<cv::Point2f>> corners(color.size());
    for (std::size_t k = 0; k < color.size(); ++k) {
        const cv::Mat gray = cv::imread(color[k].string(), cv::IMREAD_GRAYSCALE);
        cv::buildOpticalFlowPyramid(gray, pyramids[k], cv::Size(border, border), o.levels);
        cv::goodFeaturesToTrack(gray, corners[k], 400, 0.01, 8);
    }
    const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, o.max_iterations, o.epsilon);
    std::vector<cv::Point2f> to;
    std::vector<unsigned char> status;
    std::vector<float> error;
    std::size_t k = 0;
    for (auto _ : state) {
        const std::size_t a = k++ % (color.size() - 1);
        if (own)
            put_vo::track_lk(pyramids[a], pyramids[a + 1], corners[a], to, status, o);
        else
            cv::calcOpticalFlowPyrLK(pyramids[a], pyramids[a + 1], corners[a], to, status, error, o.window, o.levels, criteria);
        benchmark::DoNotOptimize(to.data());
    }
}

// The registration alone on OpenCV's threads: state.range(0) of them (the sweep's cells run with
// limits.threads, 1 by default; `vobench synth` with all).
void run_registration(benchmark::State& state) {
    const fs::path dir = synthetic("reader-kinect2-putk2", "kinect2", "putk2", 10);
    cv::Mat metres;
    cv::imread((dir / fmt_index("depth_", 0)).string(), cv::IMREAD_UNCHANGED).convertTo(metres, CV_32F, 0.001);
    const rgbd::Intrinsics d{365.5, 365.5, 255.5, 211.5, 0, {}}, c{1081.4, 1081.4, 959.5, 539.5, 0, {}};
    Eigen::Isometry3d color_from_depth = Eigen::Isometry3d::Identity();
    color_from_depth.translation() = Eigen::Vector3d(0.052, 0, 0);
    const rgbd::DepthRegistration registration(d, c, color_from_depth, metres.size(), cv::Size(1920, 1080));
    const int threads = cv::getNumThreads();
    cv::setNumThreads(static_cast<int>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(registration(metres).data);
    cv::setNumThreads(threads);
}

// The same frames from the decoded-frame cache (zstd) instead of the reader.
void run_cache(benchmark::State& state, const std::string& sensor) {
    const fs::path dir = synthetic("reader-" + sensor + "-tum", sensor, "tum", 10);
    DatasetInstance d(registry().load("tum", VOBENCH_KIND_DATASET));
    d.open(dir.string(), {});
    const FrameCache cache(fs::temp_directory_path() / ("vobench-bench-cache-" + sensor));
    for (uint64_t i = 0; i < d.info().frame_count; ++i) cache.store(i, d.read(i));
    uint64_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(cache.load(i++ % d.info().frame_count)->frame.depth->data);
    state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK_CAPTURE(run_cache, tum / kinect1_640x480, "kinect1")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_cache, tum / kinect2_1920x1080, "kinect2")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_reader, tum / kinect1_640x480, "tum", "kinect1", "tum")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_reader, tum / kinect2_1920x1080, "tum", "kinect2", "tum")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_reader, putk2 / kinect1_640x480, "putk2", "kinect1", "putk2")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_reader, putk2 / kinect2_1920x1080_registered, "putk2", "kinect2", "putk2")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(run_decode_only, opencv_imread / kinect2_1920x1080_and_512x424, "kinect2", "putk2")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(run_decode_only, opencv_imread / kinect2_1920x1080_both_tum, "kinect2", "tum")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(run_decode_part, opencv_imread / kinect2_color, "color")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_decode_part, readers_png / kinect2_color, "color own")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_decode_part, opencv_imread / kinect2_depth, "depth")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_decode_part, readers_png / kinect2_depth, "depth own")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_decode_real, opencv_imread / tum_fr1_640x480_both, false)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_decode_real, readers_png / tum_fr1_640x480_both, true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_lucas_kanade, put_vo_lk_tracker / tum_fr1_rpy_400_corners, "own")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_lucas_kanade, put_vo_lk_tracker_integer_sums / tum_fr1_rpy_400_corners, "integer")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(run_lucas_kanade, opencv_calcOpticalFlowPyrLK / tum_fr1_rpy_400_corners, "opencv")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(run_registration)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, put_vo / kinect1_640x480, "put_vo", "kinect1")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, opencv_rgbd / kinect1_640x480, "opencv_rgbd", "kinect1")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, put_vo / kinect2_1920x1080, "put_vo", "kinect2")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, opencv_rgbd / kinect2_1920x1080, "opencv_rgbd", "kinect2")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, put_vo / tum_fr1_rpy, "put_vo", "tum-fr1-rpy")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, opencv_rgbd / tum_fr1_rpy, "opencv_rgbd", "tum-fr1-rpy")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, put_vo_refresh / tum_fr1_rpy, "put_vo", "tum-fr1-rpy", ParamMap{{"profile", "refresh"}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// put_vo 1.0's default (key frames by count, ORB corners, OpenCV's LK to the bit, 500 features).
BENCHMARK_CAPTURE(run_odometry, put_vo_keyframes / tum_fr1_rpy, "put_vo", "tum-fr1-rpy", ParamMap{{"profile", "keyframes"}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// put_vo with cv::calcOpticalFlowPyrLK in place of its own tracker (lk_tracker.hpp).
BENCHMARK_CAPTURE(run_odometry, put_vo_opencv_lk / tum_fr1_rpy, "put_vo", "tum-fr1-rpy", ParamMap{{"lk_implementation", "opencv"}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// The Python bridge against the C++ null baseline, on the same decoded frames: what a Python plugin
// pays per frame before its own work (bench/python_empty.py returns a stored pose).
BENCHMARK_CAPTURE(run_odometry, constant_pose / tum_fr1_rpy, "constant_pose", "tum-fr1-rpy")->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, python_empty / tum_fr1_rpy, "python", "tum-fr1-rpy", ParamMap{{"module", VOBENCH_PYTHON_EMPTY}})
    ->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, constant_pose / kinect1_640x480, "constant_pose", "kinect1")->UseRealTime();
BENCHMARK_CAPTURE(run_odometry, python_empty / kinect1_640x480, "python", "kinect1", ParamMap{{"module", VOBENCH_PYTHON_EMPTY}})
    ->UseRealTime();
BENCHMARK_CAPTURE(run_synth, kinect1, "kinect1")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK_CAPTURE(run_synth, kinect2, "kinect2")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// The processes that read frames (vobench-worker's cells and synth, vobench track) keep frame-sized
// blocks on the heap (util/frame_memory.hpp); so does this one, or each reader would be measured
// faulting its buffers in afresh — or not, depending on which benchmark ran before it (the frame
// cache's Kinect v2 load: 7 or 85 ms).
int main(int argc, char** argv) {
    vobench::keep_frame_buffers_allocated();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
