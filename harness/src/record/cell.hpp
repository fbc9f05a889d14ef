// cell.hpp — one unit of a sweep, as its record holds it: one algorithm variant on one sequence from
// one sensor with one seed, and how it is judged and bounded. Written into cells.json and every
// run.json by the sweep, read back by the report, Slurm tasks and collect (sweep/cell.hpp expands a
// config into cells).
#pragma once

#include "abi/params.hpp"
#include "metrics/evaluation.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace vobench {

// Declared accuracy of a data set's ground truth (Ceriani et al. 2009): a metric below it is noise.
// Negative: not declared here (the reader's own declaration, if any, is used); 0: exact.
struct GroundTruthAccuracy {
    double position_m = -1;    // 1σ, m
    double rotation_deg = -1;  // 1σ, °
};

struct Limits {
    int timeout_s = 1800;       // per cell, wall clock
    uint64_t memory_mb = 4096;  // per cell, resident set
    int threads = 1;            // OpenCV/TBB threads inside a cell: 1 keeps timings comparable and -j honest
};

// How the plugin's time is taken (issue #20). offline: every frame, as fast as the plugin goes.
// realtime: frames are offered at their recorded stamps (÷ speed) on a clock that advances by the
// measured process() times; a frame that arrives while the plugin is busy is dropped, as on a robot.
// warmup_frames: the first processed frames left out of the timing statistics (not of the trajectory).
struct TimingSpec {
    std::string mode = "offline";  // "offline" | "realtime"
    double speed = 1.0;            // realtime: the stream's speed factor (2: twice as fast as recorded)
    uint64_t warmup_frames = 0;
    bool is_default() const { return mode == "offline" && speed == 1.0 && warmup_frames == 0; }
};
nlohmann::json timing_spec_json(const TimingSpec& t);
TimingSpec timing_spec_from_json(const nlohmann::json& j);  // throws on a malformed one

// One filter of a cell's chain (API 3 filter plugin), as recorded.
struct CellFilter {
    std::string plugin;  // the descriptor's name (plugin_file is what runs)
    std::string plugin_file, plugin_hash;
    ParamMap params;
};

struct Cell {
    std::string id;
    // What it runs on.
    std::string dataset, sequence, sensor, reader;
    std::string path;
    ParamMap reader_options;
    std::string dataset_checksum, reader_hash;
    GroundTruthAccuracy gt_accuracy;
    // What runs.
    std::string algorithm, plugin, plugin_file, plugin_hash, load_error;
    ParamMap params;
    uint64_t repeat = 0, seed = 1, max_frames = 0;
    // The frame count the reader declared when probed alone (sweep/sequence_probe.hpp); -1: unknown.
    // Derived from the reader and the content checksum, so not part of the id.
    int64_t frames_declared = -1;
    // The frames this cell must deliver to succeed, when known: frames_declared capped by max_frames.
    int64_t frames_required() const;
    // How it is judged and bounded.
    metrics::Protocol protocol;
    Limits limits;
    TimingSpec timing;  // in the record (and so in the id) only when not the default
    // Perturbations between reader and plugin, in order; in the record (and the id) only when present.
    std::vector<CellFilter> filters;

    // "redetect_below=100 lk_levels=3", or "defaults".
    std::string variant_label() const;
    // One entry of a table: algorithm name plus its variant, when there is a sweep, plus the filters
    // ("put_vo | depth_holes fraction=0.2") when there are any.
    std::string entry_label() const;
    // The algorithm and its variant only.
    std::string base_entry_label() const;
    // "depth_holes fraction=0.2 radius=6 + color_noise sigma=4", or "" without filters.
    std::string filter_label() const;
};

nlohmann::json cell_to_json(const Cell& cell);
Cell cell_from_json(const nlohmann::json& j);  // throws nlohmann::json::exception on a malformed record

}  // namespace vobench
