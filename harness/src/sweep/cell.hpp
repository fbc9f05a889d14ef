// cell.hpp — one unit of a sweep: one algorithm variant on one sequence from one sensor with one seed.
//
// Its id is a hash of everything that defines its result: the config slice (names, reader and its
// options, plugin and parameters, seed, frame limit, protocol), the plugin binary and the sequence's
// content. Change any of them and the cell is new; change none and `--resume` finds it done.
#pragma once

#include "sweep/sweep_config.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

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

// The full expansion, in a stable order (dataset, sequence, sensor, algorithm, variant, repeat).
// Renders synthetic sequences that are missing; remembers sequence checksums in
// <out>/.cache/checksums.json.
// With `render` false (--dry-run) nothing is rendered; a sequence not rendered yet has the checksum
// "to-render" and so a provisional id.
std::vector<Cell> expand_cells(const SweepConfig& config, const PluginRegistry& registry, const std::filesystem::path& out,
                               bool render = true);

// Shell-style wildcard (* and ?) on "dataset/sequence/sensor/algorithm/id", for `--only`.
bool cell_matches(const Cell& cell, const std::string& pattern);

}  // namespace vobench
