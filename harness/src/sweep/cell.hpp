// cell.hpp — a sweep's expansion into cells (record/cell.hpp), and `--only` matching.
//
// A cell's id is a hash of everything that defines its result: the config slice (names, reader and
// its options, plugin and parameters, seed, frame limit, protocol), the plugin binary and the
// sequence's content. Change any of them and the cell is new; change none and `--resume` finds it done.
#pragma once

#include "record/cell.hpp"
#include "sweep/sweep_config.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace vobench {

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
