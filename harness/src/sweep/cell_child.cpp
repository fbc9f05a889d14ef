// cell_child.cpp — the child side of one cell (`vobench cell-exec WORKDIR`): reads WORKDIR/cell.json,
// runs the track, streams frames.jsonl and writes sequence.json, plugin.json and result.json. It runs
// plugin code, so nothing it writes is trusted by the supervisor (cell_supervisor.cpp).
#include "sweep/cell_runner.hpp"
#include "track/track.hpp"
#include "util/files.hpp"
#include "util/subprocess.hpp"

#include <tbb/global_control.h>
#include <opencv2/core/utility.hpp>

#include <sys/prctl.h>
#include <unistd.h>
#include <csignal>
#include <cstdio>
#include <cstdlib>

namespace vobench {
namespace fs = std::filesystem;

int exec_cell(const fs::path& work) {
    // Die with the supervisor: a SIGKILLed vobench must not leave cells running into a resumed sweep.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() == 1) return 2;
    // A plugin that calls exit() does so while the frame-reading thread still runs; the static
    // destructors that exit() would run next can crash under it and turn "exited with code 3" into
    // a SIGSEGV. Registered last, this handler runs first and ends the process with the plugin's code.
    ::on_exit(
        [](int status, void*) {
            std::fflush(nullptr);
            ::_exit(status);
        },
        nullptr);
    const nlohmann::json cell_json = read_json_or_null(work / "cell.json");
    Cell cell;
    try {
        cell = cell_from_json(cell_json);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: not a cell record: %s\n", (work / "cell.json").c_str(), e.what());
        return 2;
    }
    // Before any thread exists (OpenCV's and TBB's pools, the frame reader), so all inherit it.
    const int pinned = pin_to_cell_cpu();
    cv::setNumThreads(cell.limits.threads);
    // OpenMP (Open3D's, and any plugin's) reads its thread count when libgomp is first loaded — with
    // the plugin, after this — so the limit reaches it through the environment. Without it OpenMP
    // starts one thread per core, spinning while idle, in a cell that was given one.
    const std::string omp_threads = std::to_string(cell.limits.threads);
    ::setenv("OMP_NUM_THREADS", omp_threads.c_str(), 1);
    ::setenv("OMP_WAIT_POLICY", "PASSIVE", 0);
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(cell.limits.threads));

    std::FILE* stream = std::fopen((work / "frames.jsonl").c_str(), "we");
    if (!stream) {
        std::fprintf(stderr, "cannot write %s\n", (work / "frames.jsonl").c_str());
        return 2;
    }
    TrackOptions t;
    t.dataset = cell.reader;
    t.path = cell.path;
    t.dataset_options = cell.reader_options;
    t.algorithm = cell.plugin_file.empty() ? cell.plugin : cell.plugin_file;
    t.params = cell.params;
    t.seed = cell.seed;
    t.max_frames = cell.max_frames;
    t.timing = cell.timing;
    for (const CellFilter& f : cell.filters) t.filters.push_back({f.plugin_file.empty() ? f.plugin : f.plugin_file, f.params});
    t.evaluate = false;
    // One thread means one core: frames are decoded between process() calls (still outside the
    // timed window) instead of on a prefetch thread, so N cells on N cores do not compete.
    t.prefetch_depth = cell.limits.threads > 1 ? 4 : 0;
    t.on_start = [&](const vobench_sequence_info& info, const PluginLibrary& plugin) {
        if (check_ground_truth(info).empty())
            metrics::write_tum(work / "groundtruth.txt", ground_truth_of(info), "ground truth as the reader delivered it");
        const vobench_camera& c = *info.camera;
        const uint64_t expected = cell.max_frames > 0 ? std::min(cell.max_frames, info.frame_count) : info.frame_count;
        write_json_atomic(work / "sequence.json",
                          {{"name", info.name ? info.name : ""},
                           {"sensor", info.sensor ? info.sensor : ""},
                           {"frame_count", info.frame_count},
                           {"frames_to_run", expected},
                           {"gt_count", info.gt_count},
                           // The reader's declared ground-truth accuracy (API 2; -1: not known or an API-1 reader).
                           {"gt_position_sigma_m",
                            VOBENCH_HAS_FIELD(&info, vobench_sequence_info, gt_position_sigma_m) ? info.gt_position_sigma_m : -1.0},
                           {"gt_rotation_sigma_deg",
                            VOBENCH_HAS_FIELD(&info, vobench_sequence_info, gt_rotation_sigma_deg) ? info.gt_rotation_sigma_deg : -1.0},
                           {"camera", {{"width", c.width}, {"height", c.height}, {"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}}}});
        const PluginInfo& d = plugin.info();
        write_json_atomic(work / "plugin.json", {{"name", d.name},
                                                 {"version", d.version},
                                                 {"license", d.license},
                                                 {"abi_version", d.abi_version},
                                                 {"api_version", d.api_version},
                                                 {"file", plugin.path().string()}});
    };
    std::string stream_error;  // the plugin closed or broke the stream's descriptor
    t.on_frame = [&](const FrameRecord& f, const metrics::StampedPose& p) {
        const std::string line = encode_frame(f, p);
        // fflush: into the kernel, so the frame survives the process dying on the next one.
        const bool written = std::fwrite(line.data(), 1, line.size(), stream) == line.size() && std::fflush(stream) == 0;
        if (!written && stream_error.empty())
            stream_error = "the frame stream could not be written at frame " + std::to_string(f.index) +
                           " (its file descriptor was closed or broken inside the process)";
    };
    nlohmann::json result;
    try {
        const TrackResult r = run_track(t, PluginRegistry());
        int64_t timed = 0;
        for (const FrameRecord& f : r.frames) timed += f.process_ns;
        const std::string error = r.error.empty() ? stream_error : r.error;
        result = {{"status", error.empty() ? "ok" : "failed"},
                  {"error", error},
                  {"frames", r.frames.size()},
                  {"loop_wall_ns", r.loop_wall_ns},
                  {"timed_ns", timed}};
    } catch (const std::exception& e) {  // the reader or plugin could not start: a failed row, not a crash
        result = {{"status", "failed"}, {"error", std::string("setting up: ") + e.what()}, {"frames", 0}};
    }
    std::fclose(stream);
    result["peak_rss_kb"] = peak_resident_kb("self");  // exact at the end; the supervisor's samples cover a crash
    result["affinity"] = allowed_cpus();
    result["pinned_core"] = pinned;
    write_json_atomic(work / "result.json", result);
    return 0;
}

}  // namespace vobench
