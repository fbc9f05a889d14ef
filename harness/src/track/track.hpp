// track.hpp — one odometry plugin on one sequence: the smallest useful run (`vobench track`).
//
// Frames are read and decoded ahead on another thread (FramePrefetcher), outside the timed window;
// only the plugin's process() call is timed,
// with the steady clock, in nanoseconds. Stage times and counters come from the host services.
// Evaluation happens after the loop.
#pragma once

#include "abi/instances.hpp"
#include "abi/plugin_registry.hpp"
#include "metrics/evaluation.hpp"
#include "record/cell.hpp"
#include "record/frame_stream.hpp"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vobench {

// One filter of the chain between reader and plugin (API 3 filter plugin).
struct FilterSpec {
    std::string plugin;  // name or path
    ParamMap params;
};

struct TrackOptions {
    std::string dataset;  // reader plugin name or path
    std::string path;     // sequence folder
    ParamMap dataset_options;
    std::string algorithm;  // odometry plugin name or path
    ParamMap params;
    uint64_t max_frames = 0;  // 0: all
    uint64_t seed = 1;
    metrics::Protocol protocol;
    std::filesystem::path frame_cache;  // root of the decoded-frame cache; empty: no cache
    std::size_t prefetch_depth = 4;     // frames decoded ahead on another thread; 0: on this thread
    bool evaluate = true;               // false: the caller evaluates (an isolated cell's supervisor)
    TimingSpec timing;                  // offline, or realtime (frames dropped while the plugin is busy)
    // Run in order on every frame before the plugin sees it, outside the timed window (their time is
    // counted as reading); filter k gets the seed seed + 1000003·(k+1). A frame a filter drops is
    // recorded as dropped (no pose).
    std::vector<FilterSpec> filters;
    // Called once the sequence is open and the plugin started, and after each frame, outside the
    // timed window: an isolated cell streams its results to disk so that a crash loses nothing.
    std::function<void(const vobench_sequence_info&, const PluginLibrary& odometry)> on_start;
    std::function<void(const FrameRecord&, const metrics::StampedPose&)> on_frame;
};

struct TrackResult {
    metrics::Trajectory estimate;
    std::vector<FrameRecord> frames;
    std::size_t failed_frames = 0;   // frames whose tracking status was not OK
    std::size_t dropped_frames = 0;  // real-time mode: arrived while the plugin was busy
    std::string error;               // set when the plugin or reader failed and the run stopped
    std::optional<metrics::Evaluation> evaluation;
    std::string evaluation_error;  // why there is no evaluation (no ground truth, no overlap ...)
    std::string sequence, sensor;
    int64_t loop_wall_ns = 0;  // wall time of the whole frame loop (reading included)
    double mean_ms() const;
};

// What a plugin may emit per call and per run: past these the run fails with the reason (so that a
// plugin cannot make the supervisor's work grow without bound).
constexpr std::size_t kMaxNamesPerFrame = HostContext::kMaxTracked;  // stage names, and counter names, in one call
constexpr std::size_t kMaxNamesPerRun = 1024;                        // distinct stage and counter names in one run
constexpr std::size_t kMaxNameBytes = 128;

// Runs the loop; a plugin error, a bad frame, a non-finite or non-unit pose, a non-finite counter, a
// frame stamp that is not finite or not after the previous one, and ground truth that is not finite
// each end the run with `error` naming the plugin (or reader) and the frame. Throws only when the
// plugins cannot be loaded, opened or started.
TrackResult run_track(const TrackOptions& options, const PluginRegistry& registry);

// Why the reader's ground truth cannot be used ("" when it is fine): a non-finite value or a zero
// quaternion, naming the row.
std::string check_ground_truth(const vobench_sequence_info& info);

// trajectory.txt (TUM, full precision) and timing.csv (index, stamp, process_ms, read_ms, status — ok,
// lost, failed or dropped —, one column per stage in ms, one per counter, then cpu_ms) into `dir`, each
// written atomically.
void write_track_outputs(const TrackResult& result, const std::filesystem::path& dir);

// The ground truth of an open sequence as a trajectory.
metrics::Trajectory ground_truth_of(const vobench_sequence_info& info);

}  // namespace vobench
