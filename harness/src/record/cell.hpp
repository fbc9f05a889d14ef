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

    // "redetect_below=100 lk_levels=3", or "defaults".
    std::string variant_label() const;
    // One entry of a table: algorithm name plus its variant, when there is a sweep.
    std::string entry_label() const;
};

nlohmann::json cell_to_json(const Cell& cell);
Cell cell_from_json(const nlohmann::json& j);  // throws nlohmann::json::exception on a malformed record

}  // namespace vobench
